//! `detach explore`'s latency: from a slider event (one HTTP request to a
//! running server, as the page sends it) to the certified atlas at
//! 800×600 received, per shipped scene: the coarse frame (ε = 1/64) and
//! the fine one (ε = 1/1024), over a sweep of the scene's last parameter
//! across its slider. Written to `docs/performance/explore.md`.
//!
//! The page's goal: fine ≤ 50 ms and coarse ≤ 15 ms at the 95th
//! percentile, on 2 cores.

#[path = "support/timing.rs"]
mod timing;

use detach::explore::{Config, Explorer};
use serde_json::{json, Value};
use std::fmt::Write as _;
use std::io::{Read, Write};
use std::net::TcpStream;
use std::time::Instant;
use timing::{load, utc_now};

/// One POST as the page makes it (HTTP/1.0: the body unchunked); the
/// response's JSON.
fn post(addr: std::net::SocketAddr, token: &str, path: &str, body: &Value) -> Value {
    let body = body.to_string();
    let mut s = TcpStream::connect(addr).expect("the server is up");
    write!(
        s,
        "POST {path}?token={token} HTTP/1.0\r\nHost: {addr}\r\nContent-Length: {}\r\n\
         Connection: close\r\n\r\n{body}",
        body.len()
    )
    .expect("request sent");
    let mut out = Vec::new();
    s.read_to_end(&mut out).expect("response read");
    let text = String::from_utf8_lossy(&out);
    let (_, json) = text.split_once("\r\n\r\n").expect("an HTTP response");
    serde_json::from_str(json).expect("JSON")
}

fn percentile(xs: &mut [f64], p: f64) -> f64 {
    xs.sort_by(f64::total_cmp);
    let i = ((p * xs.len() as f64).ceil() as usize).clamp(1, xs.len()) - 1;
    xs[i]
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let positions = if quick { 8 } else { 40 };
    let explorer = Explorer::start(Config::default()).expect("explorer");
    let token = explorer
        .url
        .split("token=")
        .nth(1)
        .expect("token")
        .to_string();
    let addr = explorer.addr;
    let mut table = String::new();
    writeln!(
        table,
        "| scene | parameter swept | coarse p50 | coarse p95 | fine p50 | fine p95 | leaves (fine, median) |\n|---|---|---|---|---|---|---|"
    )
    .unwrap();
    let mut seq = 0u64;
    for scene in detach::scene::Scene::names() {
        let info = post(
            addr,
            &token,
            "/api/scene",
            &json!({"client": "b", "seq": 0, "scene": scene}),
        );
        let params = info["params"].as_array().expect("params");
        let Some(p) = params.last() else { continue };
        let name = p["name"].as_str().unwrap();
        let [lo, hi] = [
            p["range"][0].as_f64().unwrap(),
            p["range"][1].as_f64().unwrap(),
        ];
        let (mut coarse, mut fine, mut leaves) = (Vec::new(), Vec::new(), Vec::new());
        for k in 0..positions {
            let v = lo + (hi - lo) * (k as f64 + 0.5) / positions as f64;
            let text = format!("{}", (v * 1e4).round() / 1e4);
            for (eps, times) in [(1.0 / 64.0, &mut coarse), (1.0 / 1024.0, &mut fine)] {
                seq += 1;
                let req = json!({"client": "b", "seq": seq, "scene": scene, "params": {name: text},
                                 "eps": eps, "width": 800, "height": 600});
                let t = Instant::now();
                let a = post(addr, &token, "/api/atlas", &req);
                times.push(t.elapsed().as_secs_f64() * 1e3);
                assert!(a.get("error").is_none(), "{scene} {name}={text}: {a}");
                if eps < 0.01 {
                    leaves.push(a["leaves"].as_f64().unwrap_or(0.0));
                }
            }
        }
        let row = format!(
            "| {scene} | {name} ∈ [{lo}, {hi}] | {:.1} ms | {:.1} ms | {:.1} ms | {:.1} ms | {:.0} |",
            percentile(&mut coarse, 0.5),
            percentile(&mut coarse, 0.95),
            percentile(&mut fine, 0.5),
            percentile(&mut fine, 0.95),
            percentile(&mut leaves, 0.5)
        );
        eprintln!("{row}");
        writeln!(table, "{row}").unwrap();
    }
    let doc = format!(
        "# `detach explore`: slider to certified atlas\n\n\
         Measured by `cargo bench --bench explore` on {} ({}), {positions} positions \
         of each scene's last parameter across its slider, one request after another \
         through a running server, 800×600 pixels: the time from sending the request \
         to the atlas (classes per pixel and the area table) received. Coarse: ε = 1/64; \
         fine: ε = 1/1024, the page's two frames.\n\n{table}\n\
         The page's goal: coarse ≤ 15 ms and fine ≤ 50 ms at the 95th percentile.\n",
        utc_now(),
        load()
    );
    if !quick {
        std::fs::write("docs/performance/explore.md", doc).expect("docs/performance/explore.md");
        eprintln!("wrote docs/performance/explore.md");
    }
}
