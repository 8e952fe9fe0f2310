//! The WebSocket handshake's Origin check. A browser sends the page's origin with
//! every handshake and lets any page open a socket to any server, so without this
//! check a page elsewhere could drive a scene with the viewer's credentials (in
//! single-user mode, with no credentials at all). Clients that are not browsers send
//! no Origin and are judged by their token alone.

/// Whether a handshake from `origin` may open a socket on the server reached as
/// `host` (the request's Host header): no Origin, the server's own origin
/// (`http://HOST` or `https://HOST`), or one of `allowed` (`--allow-origin`).
pub fn allowed(origin: Option<&str>, host: Option<&str>, allowed: &[String]) -> bool {
    let Some(origin) = origin else { return true };
    let origin = origin.trim().trim_end_matches('/');
    let own = host.is_some_and(|h| {
        ["http://", "https://"].iter().any(|scheme| {
            origin.get(..scheme.len()).is_some_and(|s| s.eq_ignore_ascii_case(scheme))
                && origin.get(scheme.len()..).is_some_and(|rest| rest.eq_ignore_ascii_case(h))
        })
    });
    own || allowed.iter().any(|a| a.trim_end_matches('/').eq_ignore_ascii_case(origin))
}

#[cfg(test)]
mod tests {
    use super::allowed;

    #[test]
    fn own_origin_listed_origins_and_non_browsers_pass() {
        let host = Some("lab.example:8080");
        let list = vec!["https://dash.example".to_string()];
        assert!(allowed(None, host, &[]));
        assert!(allowed(Some("http://lab.example:8080"), host, &[]));
        assert!(allowed(Some("HTTPS://Lab.Example:8080/"), host, &[]));
        assert!(allowed(Some("https://dash.example"), host, &list));
        assert!(!allowed(Some("http://evil.example"), host, &list));
        assert!(!allowed(Some("http://lab.example:8081"), host, &[]));
        assert!(!allowed(Some("null"), host, &[]));
        assert!(!allowed(Some("http://lab.example:8080"), None, &[]));
    }
}
