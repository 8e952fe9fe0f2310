//! Why a service call failed ([`ServiceError`]), which each transport maps to its own
//! codes, and the failures of a scene's commands and of the database as such errors.

use super::CommandError;

/// Why a request failed; each transport maps these to its own codes.
#[derive(Debug, thiserror::Error)]
pub enum ServiceError {
    /// No scene has this id, or none the caller may see (the same answer, so a
    /// scene's existence does not leak to other users).
    #[error("no scene with id {0}")]
    NotFound(u64),
    /// Something else named in the message does not exist (a user, a share link).
    #[error("{0}")]
    Missing(String),
    /// The request or the scene it carries is invalid; the message names the field.
    #[error("{0}")]
    InvalidArgument(String),
    /// The scene cannot do that in its current state.
    #[error("{0}")]
    FailedPrecondition(String),
    /// A server limit or a quota was reached; the message names it and its value.
    #[error("{0}")]
    ResourceExhausted(String),
    /// The caller may not do this (an admin-only call, or steering through a share link).
    #[error("{0}")]
    PermissionDenied(String),
    /// The database failed; the request may be retried.
    #[error("{0}")]
    Unavailable(String),
    /// In a cluster: the scene (or a new scene) is for another worker; the request
    /// goes there (through the proxy, naming the worker).
    #[error("{message}")]
    Elsewhere {
        /// The worker's name.
        worker: String,
        /// What happened, for people.
        message: String,
    },
    /// No valid credential.
    #[error("{0}")]
    Unauthenticated(#[from] crate::auth::AuthError),
}

impl From<CommandError> for ServiceError {
    fn from(e: CommandError) -> Self {
        match e {
            CommandError::BadParameter(m) | CommandError::TooFar(m) => ServiceError::InvalidArgument(m),
            CommandError::BadSnapshot(_) => ServiceError::InvalidArgument(e.to_string()),
            _ => ServiceError::FailedPrecondition(e.to_string()),
        }
    }
}

/// A database failure as a service error, logged.
pub(super) fn unavailable(e: impl std::fmt::Display) -> ServiceError {
    tracing::error!("{e}");
    ServiceError::Unavailable(format!("the server's database failed: {e}"))
}
