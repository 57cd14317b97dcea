//! Proofs hold for any correct checker, not only for detach's own: every
//! paper scene and the Painlevé rod, by every method, for the whole paving,
//! each region and a cell, stay VALID for a checker whose basic operations
//! round 2 ulps looser than tightest and whose functions round 4 ulps
//! looser (`proofs/FORMAT.md`, "Accuracy"). The proof writer confirms each
//! label on the stated text under that rounding and keeps the root box
//! inside that checker's domain (`certificate::confirm`); without it,
//! `contract` fails here on all three paper scenes (a leaf ending 2.6e-14
//! below Ω₀'s boundary on the viscous disc) and every rod proof's root box
//! ends on the tight enclosure of π/2.

use detach::check::{check_bytes, with_looseness, Looseness, Verdict};

#[test]
fn proofs_of_every_scene_and_method_hold_for_a_looser_checker() {
    let looser = Looseness {
        basic: 2,
        exact_too: false,
        functions: 4,
    };
    let dir = std::env::temp_dir().join(format!("detach-looser-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut failed = Vec::new();
    let mut checked = 0;
    for scene in ["viscous-disc", "smooth-disc", "ice-disc", "painleve-rod"] {
        for method in ["natural", "centred", "contract", "slices"] {
            for region in [
                None,
                Some("omega"),
                Some("omega0"),
                Some("omega_and_omega0"),
            ] {
                let proof = dir.join(format!("{scene}-{method}-{region:?}.json"));
                let mut args = vec!["pave", "--scene", scene, "--eps", "0.01"];
                args.extend(["--method", method, "--proof", proof.to_str().unwrap()]);
                if let Some(r) = region {
                    args.extend(["--region", r]);
                }
                let out = crate::common::detach(&args);
                assert!(
                    out.status.success(),
                    "{args:?}: {}",
                    String::from_utf8_lossy(&out.stderr)
                );
                let bytes = std::fs::read(&proof).unwrap();
                assert_eq!(check_bytes(&bytes).unwrap().verdict, Verdict::Valid);
                let r = with_looseness(looser, || check_bytes(&bytes).unwrap());
                if let Verdict::Invalid(why) = r.verdict {
                    failed.push(format!("{scene} {method} {region:?}: {why}"));
                }
                checked += 1;
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(checked, 64);
    assert!(failed.is_empty(), "{}", failed.join("\n"));
}
