//! Following a scene to its worker in a cluster (several `floe serve --worker`
//! behind one proxy). A worker that does not hold a scene answers UNAVAILABLE with
//! the holder's name in the `floe-worker` metadata, having done nothing; the client
//! then sends the call again naming that worker (the proxy routes on the header) and
//! remembers it for the scene's later calls. A call that finds no worker at all
//! (the remembered one stopped, its scenes not yet taken up by another) is sent
//! again, forgetting the worker, for up to [`FOLLOW_FOR`] if it only reads; a call
//! that changes the scene is not repeated blindly and returns the error.
//! On a single server none of this happens: it never names another worker.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use tonic::{Code, Request, Status};

/// The request header (gRPC metadata) naming the worker a call is for.
pub const WORKER_HEADER: &str = "floe-worker";

/// How long a reading call keeps looking for a scene's worker: more than a cluster's
/// default lease (10 s) plus the time to take the scene up on another worker.
pub const FOLLOW_FOR: Duration = Duration::from_secs(30);

/// How often a call is sent on to a named worker before the answer is returned (a
/// client talking to one worker directly, with no proxy, gets the same name back).
const MOST_HOPS: u32 = 3;

/// Where each scene's worker is, as last named by the cluster; `None` keys where a
/// new scene goes. Shared by a client's clones.
#[derive(Debug, Clone, Default)]
pub struct Routes(Arc<Mutex<HashMap<Option<u64>, String>>>);

/// One call's attempts.
#[derive(Debug)]
pub struct Attempt {
    target: Option<u64>,
    reads: bool,
    hops: u32,
    started: Instant,
}

impl Routes {
    /// The worker remembered for `target` (a scene, or `None` for a new scene).
    pub fn worker(&self, target: Option<u64>) -> Option<String> {
        self.0.lock().expect("lock").get(&target).cloned()
    }

    /// Forgets and returns the worker remembered for `target`.
    pub fn forget(&self, target: Option<u64>) -> Option<String> {
        self.0.lock().expect("lock").remove(&target)
    }

    /// Remembers `worker` for `target`.
    pub fn remember(&self, target: Option<u64>, worker: String) {
        self.0.lock().expect("lock").insert(target, worker);
    }

    /// `message` as a request naming `target`'s worker, when one is known.
    pub fn request<T>(&self, target: Option<u64>, message: T) -> Request<T> {
        let mut request = Request::new(message);
        if let Some(value) = self.worker(target).and_then(|w| w.parse().ok()) {
            request.metadata_mut().insert(WORKER_HEADER, value);
        }
        request
    }

    /// Starts the attempts of a call for `target`; `reads`: it changes nothing, so it
    /// may be sent again after a failure that does not say it was not carried out.
    pub fn attempt(target: Option<u64>, reads: bool) -> Attempt {
        Attempt { target, reads, hops: 0, started: Instant::now() }
    }

    /// After a failed attempt: whether to send the call again (after waiting, when
    /// no worker was named).
    pub async fn again(&self, attempt: &mut Attempt, status: &Status) -> bool {
        if status.code() != Code::Unavailable {
            return false;
        }
        let named = status.metadata().get(WORKER_HEADER).and_then(|v| v.to_str().ok()).map(str::to_owned);
        match named {
            Some(worker) => {
                attempt.hops += 1;
                self.remember(attempt.target, worker);
                attempt.hops <= MOST_HOPS
            }
            None => {
                // No worker answered (the named one stopped): the next call asks any
                // worker again. A read waits for the cluster to move the scene (which
                // names the stopped worker until its lease runs out, so the hops start
                // again); a change returns the error for its caller to retry.
                self.forget(attempt.target);
                if !attempt.reads || attempt.started.elapsed() >= FOLLOW_FOR {
                    return false;
                }
                attempt.hops = 0;
                tokio::time::sleep(Duration::from_millis(250)).await;
                true
            }
        }
    }
}

/// Sends `$message` by `$client.$method` for `$target` (a scene id or `None`),
/// following the cluster's answers ([`Routes::again`]); `$reads`: the call changes
/// nothing. Evaluates to the response or the last status.
#[macro_export]
#[doc(hidden)]
macro_rules! routed {
    ($routes:expr, $client:expr, $method:ident, $target:expr, $reads:expr, $message:expr) => {{
        let message = $message;
        let mut attempt = $crate::route::Routes::attempt($target, $reads);
        loop {
            match $client.$method($routes.request($target, message.clone())).await {
                Ok(response) => break Ok(response.into_inner()),
                Err(status) => {
                    if !$routes.again(&mut attempt, &status).await {
                        break Err($crate::ClientError::Status(status));
                    }
                }
            }
        }
    }};
}

#[cfg(test)]
mod tests {
    use super::*;

    fn named(worker: &str) -> Status {
        let mut s = Status::unavailable("scene 3 is on worker w2");
        s.metadata_mut().insert(WORKER_HEADER, worker.parse().unwrap());
        s
    }

    #[tokio::test]
    async fn a_named_worker_is_followed_and_remembered() {
        let routes = Routes::default();
        let mut a = Routes::attempt(Some(3), false);
        assert!(routes.again(&mut a, &named("w2")).await);
        assert_eq!(routes.request(Some(3), ()).metadata().get(WORKER_HEADER).unwrap(), "w2");
        assert!(routes.request(Some(4), ()).metadata().get(WORKER_HEADER).is_none(), "per scene");
        // The same name over and over: no proxy in front; the answer goes back.
        assert!(routes.again(&mut a, &named("w2")).await && routes.again(&mut a, &named("w2")).await);
        assert!(!routes.again(&mut a, &named("w2")).await);
        // Other refusals are answers.
        assert!(!routes.again(&mut Routes::attempt(Some(3), true), &Status::not_found("no scene")).await);
        // A worker gone: a change is not sent again; a read is, forgetting the worker.
        assert!(!routes.again(&mut Routes::attempt(Some(3), false), &Status::unavailable("502")).await);
        assert!(routes.worker(Some(3)).is_none(), "a change that found no worker forgets it too");
        routes.remember(Some(3), "w2".into());
        assert!(routes.again(&mut Routes::attempt(Some(3), true), &Status::unavailable("502")).await);
        assert!(routes.worker(Some(3)).is_none());
    }
}
