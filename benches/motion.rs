//! Validated integration speed: a point start integrated over 2 s on the
//! viscous disc (and 1 s on the frictionless rod), one thread, in-process;
//! the end widths are printed beside the times (the goal is width ≤ 1e-12
//! in ≤ 10 ms).

#[path = "support/timing.rs"]
mod timing;

use detach::motion::{flow, FlowRequest};
use detach::scene::{Scene, Variant};
use std::hint::black_box;
use timing::Group;

fn case(name: &str, params: &[(&str, &str)], from: (&str, &str), t: &str) -> (Scene, FlowRequest) {
    let params: Vec<(String, String)> = params
        .iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect();
    let (scene, _) = Scene::by_name(name, &params).expect("a shipped scene");
    let mut request = FlowRequest::parse(from.0, from.1, t).expect("a valid request");
    request.until = vec![];
    (scene, request)
}

fn main() {
    let group = Group::new("motion").samples(20);
    let cases = [
        (
            "viscous_disc_2s",
            case("viscous-disc", &[], ("-1.5", "1"), "2"),
        ),
        (
            "rod_mu0_1s",
            case("painleve-rod", &[("mu", "0")], ("1.3", "1.3"), "1"),
        ),
    ];
    for (label, (scene, request)) in &cases {
        let file = scene.reading(Variant::Derived);
        let tube = flow(file, request).expect("integrates");
        println!(
            "{label}: {} steps, end widths {:.1e}, {:.1e}",
            tube.len(),
            tube.end[0].wid(),
            tube.end[1].wid()
        );
        group.bench(label, || {
            flow(black_box(file), black_box(request)).map(|t| t.len())
        });
    }
}
