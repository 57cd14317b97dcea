//! The roots request: one parse, one solve (`detach::roots::request`).

use detach::roots::request::{RequestError, RootsInputs, RootsRequest};
use detach::roots::Budget;

fn request(
    equation: &str,
    kappa: Option<&str>,
    alpha: Option<&str>,
    scene: Option<&str>,
) -> Result<RootsRequest, RequestError> {
    RootsRequest::new(&RootsInputs {
        equation,
        kappa,
        alpha,
        scene,
        params: &[],
    })
}

/// Each refusal names what is wrong, in the inputs' plain names and,
/// through `message`, as a caller spells them.
#[test]
fn bad_requests_are_refused_with_what_is_wrong() {
    let flag = |e: RequestError| e.message(|i| format!("--{i}"));
    for (r, want) in [
        (request("2.11", None, None, None), "unknown equation `2.11`"),
        (
            request("2.10", None, None, None),
            "equation (2.10) needs --kappa",
        ),
        (
            request("2.9", Some("0.1"), None, None),
            "equation (2.9) needs --alpha (or --scene)",
        ),
        (
            request("2.10", Some("0.1"), Some("1"), None),
            "drop --alpha",
        ),
        (
            request("2.10", Some("0.1"), None, Some("smooth-disc")),
            "equation (2.10) takes --kappa, not --scene/--param",
        ),
        (
            request("2.12", Some("1"), None, None),
            "equation (2.12) takes --scene and --param, not --kappa/--alpha",
        ),
        (
            request("2.9", Some("0.1"), Some("0.5"), Some("smooth-disc")),
            "give either --kappa/--alpha or --scene, not both",
        ),
        (
            request("2.9", Some("0"), Some("0.5"), None),
            "κ must be positive",
        ),
        (
            request("2.9", Some("0.1"), Some("1.5"), None),
            "α must lie in [-1, 1], got 1.5",
        ),
        (
            request("3.3", None, None, Some("smooth-disc")),
            "equation (3.3) needs scene ice-disc, got smooth-disc",
        ),
        (
            request("2.9", None, None, Some("viscous-disc")),
            "equation (2.9) needs scene smooth-disc or ice-disc, got viscous-disc",
        ),
        (
            request("2.12", None, None, Some("brick")),
            "unknown scene `brick`",
        ),
        (
            request("2.9", Some("NaN"), Some("0.5"), None),
            "not a finite decimal",
        ),
    ] {
        let msg = flag(r.expect_err(want));
        assert!(msg.contains(want), "{msg:?} lacks {want:?}");
    }
    // Plain names without a caller's spelling.
    let e = request("2.10", None, None, None).unwrap_err();
    assert_eq!(e.to_string(), "equation (2.10) needs kappa");
}

/// κ must be positive: "0" is refused as not positive, "1e-330" as below
/// the doubles; " 1e-300 " is enclosed by positive doubles, its text kept
/// trimmed.
#[test]
fn kappa_must_enclose_to_positive_doubles() {
    assert_eq!(
        request("2.10", Some("0"), None, None).unwrap_err(),
        RequestError::KappaNotPositive("0".into())
    );
    assert!(matches!(
        request("2.10", Some("1e-330"), None, None),
        Err(RequestError::Param(_))
    ));
    let r = request("2.10", Some(" 1e-300 "), None, None).unwrap();
    assert_eq!(r.parameters[0].text, "1e-300");
    assert!(r.parameters[0].enclosure[0] > 0.0);
}

/// The defaults: (2.12) of the smooth disc, (3.3) of the disc on ice,
/// each with the scene's parameters as values; (2.9) of a disc derives
/// κ = g A²/(a p_M²) and α = p_m/p_M.
#[test]
fn scene_problems_default_and_derive() {
    let r = request("2.12", None, None, None).unwrap();
    assert_eq!(r.scene_name(), Some("smooth-disc"));
    assert!(r.parameters.iter().any(|p| p.name == "p_phi"));
    let r = request("3.3", None, None, None).unwrap();
    assert_eq!(r.scene_name(), Some("ice-disc"));
    let r = request("2.9", None, None, Some("smooth-disc")).unwrap();
    assert_eq!(r.derived.len(), 2);
    assert!(r.derived[1].enclosure[0] >= -1.0 && r.derived[1].enclosure[1] <= 1.0);
}

/// One solve: (2.10) at κ = 0.1 has the two positive roots of
/// μ³ − μ + 2κ = 0, (2/√3) cos(φ/3 − 2πk/3), cos φ = −3√3 κ, k = 0, 1
/// (the trigonometric form of the cubic's roots).
#[test]
fn a_request_solves_to_the_closed_form() {
    let r = request("(2.10)", Some("0.1"), None, None).unwrap();
    let sol = r.solve(&Budget::default()).unwrap();
    let phi = (-3.0 * 3f64.sqrt() * 0.1).acos();
    let mut want: Vec<f64> = [0.0, 1.0]
        .map(|k| 2.0 / 3f64.sqrt() * (phi / 3.0 - 2.0 * std::f64::consts::PI * k / 3.0).cos())
        .to_vec();
    want.sort_by(f64::total_cmp);
    assert!(sol.complete);
    assert_eq!(sol.roots.len(), 2);
    for (r, w) in sol.roots.iter().zip(want) {
        assert!(r.lo - 1e-14 <= w && w <= r.hi + 1e-14, "{r:?} {w}");
    }
}

/// The proof is built from the roots given, not solved again: from the
/// solver's two unique roots of (2.10) at κ = 0.1 it states a complete
/// result; from the same request with the roots withheld its Newton pieces
/// are missing, the roots stay undecided and the statement is incomplete.
#[test]
fn the_proof_rests_on_the_roots_given() {
    use detach::certificate::catalog::roots_proof_of;
    let r = request("2.10", Some("0.1"), None, None).unwrap();
    let mut sol = r.solve(&Budget::default()).unwrap();
    let proof = roots_proof_of(&r, &sol).unwrap();
    assert_eq!(proof["statement"]["complete"], true);
    assert_eq!(proof["statement"]["roots"].as_array().unwrap().len(), 2);
    assert_eq!(proof["statement"]["parameters"]["kappa"], "0.1");
    sol.roots.clear();
    let proof = roots_proof_of(&r, &sol).unwrap();
    assert_eq!(
        proof["statement"]["complete"], false,
        "{}",
        proof["statement"]
    );
}

/// Proof files exist for (2.9) at given κ, α, (2.10) and (2.12); a request
/// of another kind is refused, saying so.
#[test]
fn a_proof_is_refused_where_none_exists() {
    use detach::certificate::catalog::roots_proof_of;
    for (r, want) in [
        (request("3.3", None, None, None), "not for (3.3)"),
        (
            request("2.9", None, None, Some("smooth-disc")),
            "not for (2.9) of a scene",
        ),
    ] {
        let r = r.unwrap();
        let sol = r.solve(&Budget::default()).unwrap();
        let e = roots_proof_of(&r, &sol).unwrap_err();
        assert!(e.contains(want), "{e}");
    }
}
