//! The gRPC adapter of `floe.v1.LabService`: checkpoints, share links, users and
//! quotas, and every scene's statistics at once (`floectl top`).

use crate::convert::{self, status};
use crate::grpc::caller;
use crate::quota::{self, Limit};
use crate::service::{Registry, UserView};
use floe_proto::pb;
use floe_proto::pb::lab_service_server::LabService;
use std::sync::Arc;
use tonic::{Request, Response, Status};

/// The gRPC lab service.
#[derive(Debug, Clone)]
pub struct Lab {
    registry: Arc<Registry>,
}

impl Lab {
    /// A service over `registry`.
    pub fn new(registry: Arc<Registry>) -> Self {
        Self { registry }
    }

    fn shares(&self, who: &crate::auth::Caller, id: u64) -> Result<Response<pb::ShareList>, Status> {
        let share_ids = self.registry.shares(who, id).map_err(status)?;
        Ok(Response::new(pb::ShareList { scene_id: id, share_ids }))
    }
}

/// A user as a message.
pub fn user_info(u: &UserView) -> pb::UserInfo {
    pb::UserInfo {
        name: u.name.clone(),
        admin: u.admin,
        quotas: Limit::ALL
            .iter()
            .map(|&l| pb::QuotaValue {
                name: l.name().into(),
                value: u.quotas.get(l),
                overridden: u.overridden.contains(&l),
            })
            .collect(),
        scenes: u.scenes,
        running_scenes: u.running_scenes,
        running_particles: u.running_particles,
        open_streams: u.open_streams,
    }
}

type Reply<T> = Result<Response<T>, Status>;

#[tonic::async_trait]
impl LabService for Lab {
    async fn checkpoint(&self, request: Request<pb::SceneRef>) -> Reply<pb::CheckpointInfo> {
        let who = caller(&request)?;
        let id = request.into_inner().scene_id;
        let m = self.registry.checkpoint(&who, id).await.map_err(status)?;
        Ok(Response::new(pb::CheckpointInfo { scene_id: id, sequence: m.sequence, step: m.step, sim_time: m.time }))
    }

    async fn share_scene(&self, request: Request<pb::SceneRef>) -> Reply<pb::ShareLink> {
        let who = caller(&request)?;
        let id = request.into_inner().scene_id;
        let (token, share_id) = self.registry.share(&who, id).await.map_err(status)?;
        Ok(Response::new(pb::ShareLink { scene_id: id, share_id, token }))
    }

    async fn list_shares(&self, request: Request<pb::SceneRef>) -> Reply<pb::ShareList> {
        let who = caller(&request)?;
        self.shares(&who, request.into_inner().scene_id)
    }

    async fn revoke_share(&self, request: Request<pb::RevokeShareRequest>) -> Reply<pb::ShareList> {
        let who = caller(&request)?;
        let r = request.into_inner();
        self.registry.revoke_share(&who, r.scene_id, &r.share_id).await.map_err(status)?;
        self.shares(&who, r.scene_id)
    }

    async fn list_stats(&self, request: Request<pb::ListScenesRequest>) -> Reply<pb::SceneStatsList> {
        let who = caller(&request)?;
        let worker = self.registry.worker_name();
        let mut scenes: Vec<_> =
            self.registry.list(&who).iter().map(|h| convert::scene_stats(&h.shared, worker)).collect();
        scenes.extend(self.registry.placed_elsewhere(&who).iter().map(convert::placed_stats));
        scenes.sort_by_key(|s| s.scene_id);
        Ok(Response::new(pb::SceneStatsList { scenes }))
    }

    async fn who_am_i(&self, request: Request<pb::WhoAmIRequest>) -> Reply<pb::UserInfo> {
        let who = caller(&request)?;
        Ok(Response::new(user_info(&self.registry.whoami(&who).map_err(status)?)))
    }

    async fn list_users(&self, request: Request<pb::ListUsersRequest>) -> Reply<pb::ListUsersResponse> {
        let who = caller(&request)?;
        let users = self.registry.users(&who).map_err(status)?.iter().map(user_info).collect();
        Ok(Response::new(pb::ListUsersResponse { users }))
    }

    async fn set_quota(&self, request: Request<pb::SetQuotaRequest>) -> Reply<pb::UserInfo> {
        let who = caller(&request)?;
        crate::service::require_admin(&who).map_err(status)?;
        let r = request.into_inner();
        let limit = quota::limit_named(&r.quota).map_err(|m| Status::invalid_argument(format!("quota: {m}")))?;
        if r.value > 0 {
            quota::check_value(limit, r.value).map_err(|m| Status::invalid_argument(format!("value: {m}")))?;
        }
        let value = (r.value > 0).then_some(r.value);
        let user = self.registry.set_quota(&who, &r.user, limit, value).await.map_err(status)?;
        Ok(Response::new(user_info(&user)))
    }
}
