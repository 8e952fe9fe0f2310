//! The lab calls of [`Client`]: checkpoints, read-only share links, every scene's
//! statistics, the calling user, and (admins) users and quotas.

use crate::{Client, ClientError, routed};
use floe_proto::pb;

impl Client {
    /// Writes a checkpoint of a scene now.
    pub async fn checkpoint(&mut self, scene_id: u64) -> Result<pb::CheckpointInfo, ClientError> {
        routed!(self.routes, self.lab, checkpoint, Some(scene_id), false, pb::SceneRef { scene_id })
    }

    /// Creates a read-only share link of a scene; its token is shown once.
    pub async fn share(&mut self, scene_id: u64) -> Result<pb::ShareLink, ClientError> {
        routed!(self.routes, self.lab, share_scene, Some(scene_id), false, pb::SceneRef { scene_id })
    }

    /// The ids of a scene's share links.
    pub async fn shares(&mut self, scene_id: u64) -> Result<Vec<String>, ClientError> {
        Ok(routed!(self.routes, self.lab, list_shares, Some(scene_id), true, pb::SceneRef { scene_id })?.share_ids)
    }

    /// Revokes a share link; returns the ids left.
    pub async fn revoke_share(&mut self, scene_id: u64, share_id: &str) -> Result<Vec<String>, ClientError> {
        let req = pb::RevokeShareRequest { scene_id, share_id: share_id.into() };
        Ok(routed!(self.routes, self.lab, revoke_share, Some(scene_id), false, req)?.share_ids)
    }

    /// Statistics of every scene the caller can see.
    pub async fn all_stats(&mut self) -> Result<Vec<pb::SceneStats>, ClientError> {
        Ok(self.lab.list_stats(pb::ListScenesRequest {}).await?.into_inner().scenes)
    }

    /// The calling user: quotas and usage.
    pub async fn whoami(&mut self) -> Result<pb::UserInfo, ClientError> {
        Ok(self.lab.who_am_i(pb::WhoAmIRequest {}).await?.into_inner())
    }

    /// Every user (admins only).
    pub async fn users(&mut self) -> Result<Vec<pb::UserInfo>, ClientError> {
        Ok(self.lab.list_users(pb::ListUsersRequest {}).await?.into_inner().users)
    }

    /// Sets a user's quota (admins only); `value` 0 clears the override.
    pub async fn set_quota(&mut self, user: &str, quota: &str, value: u64) -> Result<pb::UserInfo, ClientError> {
        let req = pb::SetQuotaRequest { user: user.into(), quota: quota.into(), value };
        Ok(self.lab.set_quota(req).await?.into_inner())
    }
}
