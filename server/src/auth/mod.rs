//! Who is calling: users with API tokens, read-only share links, or, in
//! single-user mode (no tokens), the built-in `local` administrator.
//!
//! The server keeps users, token hashes, quota overrides and share links in memory
//! ([`Directory`], read from the database) so authenticating a call never waits on
//! the database; it re-reads them when their version in the database changes (a
//! change by `floe admin` reaches a running server within a second).
//!
//! - [`token`]: token format and hashing.
//! - [`origin`]: the WebSocket handshake's Origin check.

pub mod origin;
pub mod token;

use crate::quota::{Limit, QuotaSet};
use crate::store::db::DirectoryRows;
use std::collections::HashMap;
use std::sync::{Arc, RwLock};

/// Name of the user every call is made by in single-user mode.
pub const LOCAL_USER: &str = "local";

/// Who makes a call.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Caller {
    /// A user.
    User {
        /// Login name.
        name: Arc<str>,
        /// May call admin-only endpoints and sees every scene.
        admin: bool,
    },
    /// A read-only share link of one scene: may watch it, not steer it.
    Viewer {
        /// The shared scene.
        scene: u64,
    },
}

impl Caller {
    /// The administrator of a single-user server.
    pub fn local() -> Self {
        Caller::User { name: LOCAL_USER.into(), admin: true }
    }

    /// Whether the caller may call admin-only endpoints.
    pub fn is_admin(&self) -> bool {
        matches!(self, Caller::User { admin: true, .. })
    }
}

/// How calls are authenticated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AuthMode {
    /// Every call is made by the `local` administrator; credentials are ignored.
    SingleUser,
    /// Every call but health checks, reflection and the viewer's files needs a token.
    Tokens,
}

/// Why a call was not authenticated (UNAUTHENTICATED / 401).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum AuthError {
    /// No credential.
    #[error("this server needs an API token: send 'authorization: Bearer <token>' (floectl: --token or FLOE_TOKEN)")]
    Missing,
    /// Not `Bearer <token>`.
    #[error("the authorization header must be 'Bearer <token>'")]
    Malformed,
    /// Not a token this server knows (mistyped, revoked or rotated).
    #[error("the token is not valid: it was revoked, rotated or mistyped")]
    Unknown,
}

/// A user as the server knows it.
#[derive(Debug, Clone, PartialEq)]
pub struct User {
    /// May call admin-only endpoints.
    pub admin: bool,
    /// The user's quota overrides.
    pub overrides: Vec<(Limit, u64)>,
}

/// Users, token hashes, quota overrides and share links, as of one database version.
#[derive(Debug, Clone, Default)]
pub struct Directory {
    /// The database version these were read at.
    pub version: i64,
    users: HashMap<String, User>,
    tokens: HashMap<String, String>,
    shares: HashMap<String, u64>,
}

impl Directory {
    /// The directory of these database rows; unknown quota names (from a newer
    /// build) are skipped with a warning.
    pub fn from_rows(rows: DirectoryRows) -> Self {
        let mut users: HashMap<String, User> =
            rows.users.into_iter().map(|u| (u.name, User { admin: u.admin, overrides: Vec::new() })).collect();
        for (user, quota, value) in rows.quotas {
            match (Limit::from_name(&quota), users.get_mut(&user)) {
                (Some(limit), Some(u)) => u.overrides.push((limit, value.max(1) as u64)),
                (None, _) => tracing::warn!("unknown quota '{quota}' of user {user} ignored"),
                (_, None) => {}
            }
        }
        Self {
            version: rows.version,
            users,
            tokens: rows.tokens.into_iter().collect(),
            shares: rows.shares.into_iter().collect(),
        }
    }

    /// A user by name.
    pub fn user(&self, name: &str) -> Option<&User> {
        self.users.get(name)
    }

    /// Every user, in no particular order.
    pub fn users(&self) -> impl Iterator<Item = (&String, &User)> {
        self.users.iter()
    }

    /// Share ids of `scene`'s links.
    pub fn shares_of(&self, scene: u64) -> Vec<String> {
        let mut ids: Vec<String> = self
            .shares
            .iter()
            .filter(|&(_, &s)| s == scene)
            .map(|(hash, _)| hash[..token::SHARE_ID_LEN].to_owned())
            .collect();
        ids.sort();
        ids
    }
}

/// Authentication and the directory behind it.
#[derive(Debug)]
pub struct Access {
    mode: AuthMode,
    directory: RwLock<Arc<Directory>>,
    /// Origins besides the server's own that may open a WebSocket.
    origins: Vec<String>,
}

impl Access {
    /// Access in `mode`, with these extra allowed WebSocket origins.
    pub fn new(mode: AuthMode, origins: Vec<String>) -> Self {
        Self { mode, directory: RwLock::default(), origins }
    }

    /// The mode.
    pub fn mode(&self) -> AuthMode {
        self.mode
    }

    /// Origins besides the server's own allowed to open a WebSocket.
    pub fn origins(&self) -> &[String] {
        &self.origins
    }

    /// The directory now.
    pub fn directory(&self) -> Arc<Directory> {
        self.directory.read().expect("lock").clone()
    }

    /// Replaces the directory.
    pub fn set_directory(&self, d: Directory) {
        *self.directory.write().expect("lock") = Arc::new(d);
    }

    /// The caller presenting `credential` (a token, without `Bearer `), if any.
    pub fn authenticate(&self, credential: Option<&str>) -> Result<Caller, AuthError> {
        if self.mode == AuthMode::SingleUser {
            return Ok(Caller::local());
        }
        let credential = credential.ok_or(AuthError::Missing)?;
        let directory = self.directory();
        if token::well_formed(credential, token::API_PREFIX) {
            let name = directory.tokens.get(&token::hash(credential)).ok_or(AuthError::Unknown)?;
            let user = directory.users.get(name).ok_or(AuthError::Unknown)?;
            return Ok(Caller::User { name: name.as_str().into(), admin: user.admin });
        }
        if token::well_formed(credential, token::SHARE_PREFIX) {
            let &scene = directory.shares.get(&token::hash(credential)).ok_or(AuthError::Unknown)?;
            return Ok(Caller::Viewer { scene });
        }
        Err(AuthError::Unknown)
    }

    /// The token in an `authorization` header value (`Bearer <token>`).
    pub fn bearer(header: &str) -> Result<&str, AuthError> {
        let (scheme, token) = header.trim().split_once(' ').ok_or(AuthError::Malformed)?;
        if !scheme.eq_ignore_ascii_case("bearer") {
            return Err(AuthError::Malformed);
        }
        Ok(token.trim())
    }

    /// The quotas of user `name`: the defaults with the user's overrides.
    pub fn quotas_of(&self, name: &str, defaults: QuotaSet) -> QuotaSet {
        let mut set = defaults;
        if let Some(u) = self.directory().users.get(name) {
            for &(limit, value) in &u.overrides {
                set.set(limit, value);
            }
        }
        set
    }
}

/// The protocol a WebSocket client offers (and the server selects) besides its token.
pub const WS_PROTOCOL: &str = "floe.v1";

/// The credential of a request: the `authorization: Bearer <token>` header, or for a
/// WebSocket (browsers cannot set headers on one) a token offered as one of its
/// protocols (`new WebSocket(url, ["floe.v1", token])`), which keeps it out of URLs
/// and so out of logs.
pub fn credential(headers: &axum::http::HeaderMap) -> Result<Option<&str>, AuthError> {
    if let Some(value) = headers.get(axum::http::header::AUTHORIZATION) {
        return Access::bearer(value.to_str().map_err(|_| AuthError::Malformed)?).map(Some);
    }
    let offered = headers
        .get_all(axum::http::header::SEC_WEBSOCKET_PROTOCOL)
        .iter()
        .filter_map(|v| v.to_str().ok())
        .flat_map(|v| v.split(','))
        .map(str::trim)
        .find(|p| p.starts_with(token::API_PREFIX) || p.starts_with(token::SHARE_PREFIX));
    Ok(offered)
}

/// Authenticates a request by its headers and takes one call from its request rate.
pub fn authorize(
    registry: &crate::service::Registry,
    headers: &axum::http::HeaderMap,
) -> Result<Caller, crate::service::ServiceError> {
    let caller = registry.access().authenticate(credential(headers)?)?;
    registry.admit(&caller)?;
    Ok(caller)
}

/// Whether `name` may name a user: 1 to 64 of `a-z 0-9 _ . -`, starting with a letter
/// or digit (it appears in URLs, logs and metric labels).
pub fn valid_user_name(name: &str) -> bool {
    (1..=64).contains(&name.len())
        && name.bytes().all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b"_.-".contains(&b))
        && name.as_bytes()[0].is_ascii_alphanumeric()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::store::db::UserRow;

    #[test]
    fn tokens_and_share_links_authenticate() {
        let (alice, link) = (token::generate(token::API_PREFIX), token::generate(token::SHARE_PREFIX));
        let access = Access::new(AuthMode::Tokens, Vec::new());
        access.set_directory(Directory::from_rows(DirectoryRows {
            version: 1,
            users: vec![UserRow { name: "alice".into(), admin: false }],
            tokens: vec![(token::hash(&alice), "alice".into())],
            quotas: vec![("alice".into(), "open_streams".into(), 3), ("alice".into(), "bogus".into(), 1)],
            shares: vec![(token::hash(&link), 9)],
        }));
        assert_eq!(access.authenticate(Some(&alice)), Ok(Caller::User { name: "alice".into(), admin: false }));
        assert_eq!(access.authenticate(Some(&link)), Ok(Caller::Viewer { scene: 9 }));
        assert_eq!(access.authenticate(None), Err(AuthError::Missing));
        assert_eq!(access.authenticate(Some(&token::generate(token::API_PREFIX))), Err(AuthError::Unknown));
        assert_eq!(access.authenticate(Some("hunter2")), Err(AuthError::Unknown));
        assert_eq!(access.quotas_of("alice", QuotaSet::default()).get(Limit::OpenStreams), 3);
        assert_eq!(Access::bearer("Bearer abc"), Ok("abc"));
        assert_eq!(Access::bearer("Basic abc"), Err(AuthError::Malformed));
        let single = Access::new(AuthMode::SingleUser, Vec::new());
        assert_eq!(single.authenticate(Some("anything")), Ok(Caller::local()));
    }

    #[test]
    fn user_names() {
        assert!(valid_user_name("alice") && valid_user_name("r2.d-2_x"));
        assert!(!valid_user_name("") && !valid_user_name("-x") && !valid_user_name("Alice") && !valid_user_name("a b"));
        assert!(!valid_user_name(&"a".repeat(65)));
    }
}
