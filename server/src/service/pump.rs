//! Feeds: a subscription's frames or a scene's events moved by a task of their own
//! into a channel a transport reads (a gRPC response stream, a WebSocket's loop).
//!
//! The task ends as soon as the transport drops its end, even while the scene is
//! paused and nothing new comes: a client that vanished (an abrupt close, a TCP
//! reset) stops counting as a subscriber and an open stream at once, not at the
//! scene's next step.

use super::frames::{EncodedFrame, Subscription};
use super::shared::{Event, Shared};
use crate::quota::StreamPermit;
use floe_proto::EncodeError;
use std::sync::Arc;
use std::sync::atomic::Ordering;
use tokio::sync::{broadcast, mpsc};

/// A frame subscription and the stream quota it holds.
#[derive(Debug)]
pub struct FrameFeed {
    pub(super) subscription: Subscription,
    pub(super) permit: StreamPermit,
    pub(super) shared: Arc<Shared>,
}

impl FrameFeed {
    /// What changes the stream's region of interest while it is open.
    pub fn view_control(&self) -> super::frames::ViewControl {
        self.subscription.view_control()
    }

    /// Starts moving frames, each made into a `T` by `map`. Capacity 1: a frame waits
    /// for the reader only while the next one is made, so a slow reader skips
    /// frames instead of queueing them. Frame bytes handed over count as sent.
    pub fn spawn<T: Send + 'static>(
        self,
        map: impl Fn(Result<EncodedFrame, EncodeError>) -> T + Send + 'static,
    ) -> mpsc::Receiver<T> {
        let (tx, rx) = mpsc::channel(1);
        let Self { mut subscription, permit, shared } = self;
        tokio::spawn(async move {
            let _permit = permit;
            loop {
                let frame = tokio::select! {
                    frame = subscription.next() => frame,
                    () = tx.closed() => break,
                };
                let Some(frame) = frame else { break };
                let bytes = frame.as_ref().map_or(0, |f| f.data.len() as u64);
                if tx.send(map(frame)).await.is_err() {
                    break;
                }
                shared.frame_bytes.fetch_add(bytes, Ordering::Relaxed);
            }
        });
        rx
    }
}

/// A scene's events and the stream quota they hold.
#[derive(Debug)]
pub struct EventFeed {
    pub(super) events: broadcast::Receiver<Event>,
    pub(super) permit: StreamPermit,
}

impl EventFeed {
    /// Starts moving events, each made into a `T` by `map`, until the scene is deleted
    /// (that event included) or the reader is gone.
    pub fn spawn<T: Send + 'static>(self, map: impl Fn(Event) -> T + Send + 'static) -> mpsc::Receiver<T> {
        let (tx, rx) = mpsc::channel(16);
        let Self { mut events, permit } = self;
        tokio::spawn(async move {
            let _permit = permit;
            loop {
                let event = tokio::select! {
                    e = events.recv() => e,
                    () = tx.closed() => break,
                };
                let event = match event {
                    Ok(e) => e,
                    Err(broadcast::error::RecvError::Lagged(_)) => continue,
                    Err(broadcast::error::RecvError::Closed) => break,
                };
                let last = event == Event::Deleted;
                if tx.send(map(event)).await.is_err() || last {
                    break;
                }
            }
        });
        rx
    }
}
