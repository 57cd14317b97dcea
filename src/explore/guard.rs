//! What a request must show before the server does any work for it: the
//! session's random token, a Host header naming the address served (so a
//! page of another site that rebinds its DNS name to 127.0.0.1 is refused),
//! and a body no larger than [`MAX_BODY`].

use std::net::SocketAddr;

/// Largest request body read (a scene file and its parameters).
pub const MAX_BODY: usize = 256 * 1024;

/// Why a request is refused, with the status it is answered with.
#[derive(Debug, PartialEq, Eq)]
pub enum Refusal {
    /// 403: no token, or not this session's.
    Token,
    /// 403: the Host header names another address.
    Host(String),
    /// 413: the body is larger than [`MAX_BODY`].
    TooLarge,
}

impl Refusal {
    pub fn status(&self) -> u16 {
        match self {
            Refusal::Token | Refusal::Host(_) => 403,
            Refusal::TooLarge => 413,
        }
    }

    pub fn message(&self) -> String {
        match self {
            Refusal::Token => "this page needs the token printed by `detach explore`".into(),
            Refusal::Host(h) => format!("refused Host `{h}`: not the address served"),
            Refusal::TooLarge => format!("request body over {} KiB", MAX_BODY / 1024),
        }
    }
}

/// A fresh session token: 128 random bits from the operating system, as
/// 32 hex digits.
pub fn new_token() -> Result<String, String> {
    let mut bytes = [0u8; 16];
    getrandom::fill(&mut bytes).map_err(|e| format!("no random source for the token: {e}"))?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

/// The `token` of a URL's query (`/api/atlas?token=…&x=1`), if any.
pub fn token_of(url: &str) -> Option<&str> {
    let query = url.split_once('?')?.1;
    query
        .split('&')
        .find_map(|kv| kv.strip_prefix("token="))
        .map(|t| t.split('#').next().unwrap_or(t))
}

/// Equal in time independent of where the strings first differ.
fn same(a: &str, b: &str) -> bool {
    a.len() == b.len()
        && a.bytes()
            .zip(b.bytes())
            .fold(0u8, |acc, (x, y)| acc | (x ^ y))
            == 0
}

/// The Host values that name `addr`: `IP:PORT`, and for loopback also
/// `localhost:PORT`.
pub fn hosts_served(addr: SocketAddr) -> Vec<String> {
    let port = addr.port();
    let mut out = vec![match addr {
        SocketAddr::V4(a) => format!("{}:{port}", a.ip()),
        SocketAddr::V6(a) => format!("[{}]:{port}", a.ip()),
    }];
    if addr.ip().is_loopback() {
        out.push(format!("localhost:{port}"));
    }
    out
}

/// Admits a request by its URL, Host header and declared body length.
pub fn admit(
    url: &str,
    host: Option<&str>,
    body_length: Option<usize>,
    token: &str,
    served: &[String],
) -> Result<(), Refusal> {
    let host = host.unwrap_or("").trim();
    if !served.iter().any(|s| s.eq_ignore_ascii_case(host)) {
        return Err(Refusal::Host(host.chars().take(80).collect()));
    }
    match token_of(url) {
        Some(t) if same(t, token) => {}
        _ => return Err(Refusal::Token),
    }
    if body_length.is_some_and(|n| n > MAX_BODY) {
        return Err(Refusal::TooLarge);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn served() -> Vec<String> {
        hosts_served("127.0.0.1:8123".parse().unwrap())
    }

    #[test]
    fn tokens_are_fresh_hex() {
        let (a, b) = (new_token().unwrap(), new_token().unwrap());
        assert_eq!(a.len(), 32);
        assert!(a.bytes().all(|c| c.is_ascii_hexdigit()));
        assert_ne!(a, b, "two sessions share a token");
    }

    #[test]
    fn the_token_is_read_from_the_query_only() {
        assert_eq!(token_of("/?token=ab12"), Some("ab12"));
        assert_eq!(token_of("/api/atlas?x=1&token=ab12&y=2"), Some("ab12"));
        assert_eq!(token_of("/token=ab12"), None);
        assert_eq!(token_of("/?tokens=ab12"), None);
    }

    #[test]
    fn a_request_needs_token_host_and_a_small_body() {
        let s = served();
        let ok = |url, host, len| admit(url, host, len, "abc", &s);
        assert_eq!(ok("/?token=abc", Some("127.0.0.1:8123"), None), Ok(()));
        assert_eq!(ok("/?token=abc", Some("localhost:8123"), Some(10)), Ok(()));
        assert_eq!(ok("/", Some("127.0.0.1:8123"), None), Err(Refusal::Token));
        assert_eq!(
            ok("/?token=abd", Some("127.0.0.1:8123"), None),
            Err(Refusal::Token)
        );
        assert_eq!(
            ok("/?token=ab", Some("127.0.0.1:8123"), None),
            Err(Refusal::Token)
        );
        // DNS rebinding: the right address under another name, or another port.
        assert!(matches!(
            ok("/?token=abc", Some("evil.example:8123"), None),
            Err(Refusal::Host(_))
        ));
        assert!(matches!(
            ok("/?token=abc", Some("127.0.0.1:8124"), None),
            Err(Refusal::Host(_))
        ));
        assert!(matches!(
            ok("/?token=abc", None, None),
            Err(Refusal::Host(_))
        ));
        assert_eq!(
            ok("/?token=abc", Some("127.0.0.1:8123"), Some(MAX_BODY + 1)),
            Err(Refusal::TooLarge)
        );
        assert_eq!(Refusal::TooLarge.status(), 413);
    }

    #[test]
    fn only_loopback_is_served_as_localhost() {
        let lan = hosts_served("192.168.1.5:80".parse().unwrap());
        assert_eq!(lan, vec!["192.168.1.5:80".to_string()]);
        let v6 = hosts_served("[::1]:9000".parse().unwrap());
        assert_eq!(v6, vec!["[::1]:9000".to_string(), "localhost:9000".into()]);
    }
}
