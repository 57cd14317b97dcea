//! `detach explore`: a local page where the certified atlas follows the
//! parameters. A small HTTP server ([`tiny_http`]) on loopback serves one
//! page, shipped in the binary, and a JSON API the page calls; every
//! number on the page comes from the same library calls as the command
//! line's (`pave`, `params`, `flow`), so the page's area table is `detach
//! pave`'s at the same resolution.
//!
//! Stages, one module each: [`guard`] admits a request (token, Host, body
//! size), [`jobs`] schedules it (superseded requests cancelled, at most
//! [`CONCURRENT`] computations, a budget each), [`views`] computes it.
//! The server never reads or writes a path a request names: downloads are
//! built in a folder of its own and sent as bytes.

pub mod guard;
pub mod jobs;
pub mod views;

use crate::api::{Error, ErrorKind};
use jobs::{Budget, Latest, Slots, Ticket};
use serde_json::{json, Value};
use std::io::Read;
use std::net::{IpAddr, SocketAddr};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;
use tiny_http::{Header, Request, Response, Server};

/// The page: HTML, CSS and script in one file, no network needed.
const PAGE: &str = include_str!("page.html");

/// Computations running at once (the machine's cores are shared by the
/// paving's own threads).
pub const CONCURRENT: usize = 2;
/// Threads answering requests: more than [`CONCURRENT`], so the page and a
/// fresh atlas are answered while a parameter plane computes.
const WORKERS: usize = 6;

/// How to start an explorer.
#[derive(Clone, Debug)]
pub struct Config {
    /// The scene shown first, by name (`painleve-rod`, `viscous-disc`, …).
    pub scene: Option<String>,
    /// Or a scene file's text (what `--scene-file` read), shown and edited.
    pub scene_text: Option<String>,
    /// Parameters the page starts with, `(name, decimal text)`; the
    /// scene's own values for the others.
    pub params: Vec<(String, String)>,
    /// The address to bind: loopback unless said otherwise.
    pub ip: IpAddr,
    /// 0: any free port.
    pub port: u16,
    /// Per request: time and leaves of an atlas or a download.
    pub atlas_budget: Budget,
    /// Per request: time and boxes of a parameter plane.
    pub params_budget: Budget,
}

impl Default for Config {
    fn default() -> Self {
        Config {
            scene: Some("painleve-rod".into()),
            scene_text: None,
            params: Vec::new(),
            ip: IpAddr::from([127, 0, 0, 1]),
            port: 0,
            atlas_budget: Budget {
                time: Duration::from_secs(10),
                leaves: 4_000_000,
            },
            params_budget: Budget {
                time: Duration::from_secs(30),
                leaves: 20_000,
            },
        }
    }
}

/// What every worker shares.
struct Shared {
    config: Config,
    token: String,
    served: Vec<String>,
    latest: Latest,
    slots: Slots,
    /// Downloads are built here, then sent and removed.
    scratch: PathBuf,
    /// The scene and parameters of the page's last atlas.
    state: Mutex<Value>,
}

/// A running explorer; stops when dropped.
pub struct Explorer {
    /// The page's address, token included.
    pub url: String,
    pub addr: SocketAddr,
    server: Arc<Server>,
    shared: Arc<Shared>,
    workers: Vec<JoinHandle<()>>,
}

impl Explorer {
    /// Binds and starts serving. Fails on a scene that does not load, a
    /// port in use, or no random source for the token.
    pub fn start(config: Config) -> Result<Explorer, Error> {
        let first = first_request(&config);
        views::problem_of(&first)?;
        let token = guard::new_token().map_err(|e| Error::new(ErrorKind::Computation, e))?;
        let at = SocketAddr::new(config.ip, config.port);
        let server = Server::http(at).map_err(|e| match e.downcast::<std::io::Error>() {
            Ok(io) => Error::io("listen on", &at.to_string(), &io),
            Err(e) => Error::new(
                ErrorKind::Computation,
                format!("cannot listen on {at}: {e}"),
            ),
        })?;
        let addr = server.server_addr().to_ip().ok_or_else(|| {
            Error::new(ErrorKind::Computation, "the server is not on an IP address")
        })?;
        let scratch = std::env::temp_dir().join(format!("detach-explore-{}", &token[..12]));
        std::fs::create_dir_all(&scratch)
            .map_err(|e| Error::io("make", &scratch.display().to_string(), &e))?;
        let served = guard::hosts_served(addr);
        let url = format!("http://{}/?token={token}", served[0]);
        let shared = Arc::new(Shared {
            state: Mutex::new(first),
            config,
            token,
            served,
            latest: Latest::default(),
            slots: Slots::new(CONCURRENT),
            scratch,
        });
        let server = Arc::new(server);
        let workers = (0..WORKERS)
            .map(|_| {
                let (server, shared) = (server.clone(), shared.clone());
                std::thread::spawn(move || {
                    while let Ok(rq) = server.recv() {
                        answer(&shared, rq);
                    }
                })
            })
            .collect();
        Ok(Explorer {
            url,
            addr,
            server,
            shared,
            workers,
        })
    }

    /// The scene (name or edited text) and parameters of the page's last
    /// atlas: `{"scene", "text"?, "params": {name: text}}`.
    pub fn state(&self) -> Value {
        self.shared
            .state
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .clone()
    }

    /// Stops serving and waits for the workers.
    pub fn stop(&mut self) {
        for _ in &self.workers {
            self.server.unblock();
        }
        for w in self.workers.drain(..) {
            w.join().ok();
        }
        std::fs::remove_dir_all(&self.shared.scratch).ok();
    }

    /// Serves until the process is stopped.
    pub fn wait(mut self) {
        for w in self.workers.drain(..) {
            w.join().ok();
        }
    }
}

impl Drop for Explorer {
    fn drop(&mut self) {
        self.stop();
    }
}

/// The request the page starts from.
fn first_request(config: &Config) -> Value {
    let params: serde_json::Map<String, Value> = config
        .params
        .iter()
        .map(|(n, t)| (n.clone(), json!(t)))
        .collect();
    match (&config.scene_text, &config.scene) {
        (Some(text), name) => json!({"scene": name, "text": text, "params": params}),
        (None, name) => {
            json!({"scene": name.as_deref().unwrap_or("painleve-rod"), "params": params})
        }
    }
}

fn header(name: &str, value: &str) -> Header {
    Header::from_bytes(name.as_bytes(), value.as_bytes()).expect("ASCII header")
}

/// A response with the headers every answer carries: no caching, no
/// sniffing, no referrer (the token is in the URL), nothing from elsewhere.
fn respond(rq: Request, status: u16, kind: &str, body: Vec<u8>, extra: Option<Header>) {
    let mut r = Response::from_data(body)
        .with_status_code(status)
        .with_header(header("Content-Type", kind))
        .with_header(header("Cache-Control", "no-store"))
        .with_header(header("X-Content-Type-Options", "nosniff"))
        .with_header(header("Referrer-Policy", "no-referrer"))
        .with_header(header(
            "Content-Security-Policy",
            "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; \
             img-src data: blob:; connect-src 'self'",
        ));
    if let Some(h) = extra {
        r = r.with_header(h);
    }
    // The page may have gone (an aborted request): nothing to do then.
    rq.respond(r).ok();
}

fn respond_json(rq: Request, status: u16, v: &Value) {
    let body = serde_json::to_vec(v).expect("serialisable");
    respond(rq, status, "application/json", body, None);
}

fn error(rq: Request, status: u16, message: &str) {
    respond_json(rq, status, &json!({"error": message}));
}

/// Admits, schedules and answers one request.
fn answer(shared: &Shared, mut rq: Request) {
    let host = rq
        .headers()
        .iter()
        .find(|h| h.field.equiv("Host"))
        .map(|h| h.value.as_str().to_string());
    let url = rq.url().to_string();
    if let Err(r) = guard::admit(
        &url,
        host.as_deref(),
        rq.body_length(),
        &shared.token,
        &shared.served,
    ) {
        return error(rq, r.status(), &r.message());
    }
    let path = url.split('?').next().unwrap_or("");
    let method = rq.method().as_str().to_string();
    match (method.as_str(), path) {
        ("GET", "/") => {
            let page = PAGE.replace("__TOKEN__", &shared.token);
            respond(rq, 200, "text/html; charset=utf-8", page.into_bytes(), None)
        }
        ("POST", "/api/scene" | "/api/atlas" | "/api/params" | "/api/flow" | "/api/download") => {
            let mut body = Vec::new();
            let read = rq
                .as_reader()
                .take(guard::MAX_BODY as u64 + 1)
                .read_to_end(&mut body);
            if read.is_err() {
                return error(rq, 400, "the request body could not be read");
            }
            if body.len() > guard::MAX_BODY {
                let r = guard::Refusal::TooLarge;
                return error(rq, r.status(), &r.message());
            }
            match serde_json::from_slice::<Value>(&body) {
                Ok(req) if req.is_object() => api(shared, rq, path, &req),
                _ => error(rq, 400, "the request body must be a JSON object"),
            }
        }
        _ => error(rq, 404, "no such page"),
    }
}

/// The API: one view per path, scheduled through [`jobs`].
fn api(shared: &Shared, rq: Request, path: &str, req: &Value) {
    let client = req.get("client").and_then(Value::as_str).unwrap_or("");
    let seq = req.get("seq").and_then(Value::as_u64).unwrap_or(0);
    let channel = path.trim_start_matches("/api/");
    let key = format!("{client}/{channel}");
    if !shared.latest.arrive(&key, seq) {
        return respond_json(rq, 200, &json!({"superseded": true}));
    }
    let budget = match channel {
        "params" => shared.config.params_budget,
        _ => shared.config.atlas_budget,
    };
    let ticket = Ticket::new(&shared.latest, key, seq, budget);
    let Some(_slot) = shared.slots.take(|| !ticket.superseded()) else {
        return respond_json(rq, 200, &json!({"superseded": true}));
    };
    let start_text = shared.config.scene_text.as_deref();
    let first;
    let req = if req.get("start").and_then(Value::as_bool) == Some(true) {
        first = first_request(&shared.config);
        &first
    } else {
        req
    };
    let result = match channel {
        "scene" => views::scene(req, start_text),
        "atlas" => views::atlas(req, &ticket).inspect(|v| remember(shared, req, &v["params"])),
        "params" => views::param_plane(req, &ticket),
        "flow" => views::flow(req),
        _ => match views::download(req, &ticket, &shared.scratch) {
            Ok((name, bytes)) => {
                let kind = match name.rsplit('.').next() {
                    Some("svg") => "image/svg+xml",
                    Some("png") => "image/png",
                    Some("csv") => "text/csv",
                    _ => "application/json",
                };
                let disposition = header(
                    "Content-Disposition",
                    &format!("attachment; filename=\"{name}\""),
                );
                return respond(rq, 200, kind, bytes, Some(disposition));
            }
            Err(e) => Err(e),
        },
    };
    match result {
        _ if ticket.cut() == Some(jobs::Cut::Superseded) => {
            respond_json(rq, 200, &json!({"superseded": true}))
        }
        Ok(mut v) => {
            v["seq"] = json!(seq);
            respond_json(rq, 200, &v)
        }
        Err(e) => error(rq, 400, &e),
    }
}

/// Keeps the scene and every parameter of the last atlas drawn.
fn remember(shared: &Shared, req: &Value, params: &Value) {
    let mut state = json!({"scene": req.get("scene"), "params": params});
    if let Some(t) = req.get("text") {
        state["text"] = t.clone();
    }
    *shared.state.lock().unwrap_or_else(|e| e.into_inner()) = state;
}
