//! The cluster's rules on one SQLite database.

use super::*;

fn info(name: &str, max_particles: u64) -> WorkerInfo {
    WorkerInfo {
        name: name.into(),
        grpc: format!("{name}:50051"),
        http: format!("{name}:8080"),
        backend: "cpu".into(),
        max_scenes: 8,
        max_particles,
    }
}

fn scene(id: u64, particles: u64, lease: &Lease) -> SceneRow {
    SceneRow {
        id,
        owner: "ada".into(),
        name: format!("s{id}"),
        spec: "{}".into(),
        tunables: "{}".into(),
        state: "running".into(),
        real_time_factor: 1.0,
        particles,
        lease: Some(lease.clone()),
        generation: 0,
    }
}

/// The cluster's rules on one database; `floe serve`'s cluster test runs them
/// on PostgreSQL with real workers.
#[tokio::test]
async fn leases_fence_writes_and_evicted_scenes_move_paused() {
    let dir = tempfile::tempdir().unwrap();
    let db = Database::open(&format!("sqlite://{}?mode=rwc", dir.path().join("c.db").display())).await.unwrap();
    let a = db.register_worker(&info("a", 1000)).await.unwrap();
    let b = db.register_worker(&info("b", 1000)).await.unwrap();
    let c = db.register_worker(&info("c", 2000)).await.unwrap();
    assert!(a.epoch < b.epoch && b.epoch < c.epoch, "epochs are unique over the cluster");
    let first = db.take_scene_id().await.unwrap();
    assert_eq!(db.take_scene_id().await.unwrap(), first + 1);
    db.insert_scene(&scene(first, 600, &a)).await.unwrap();
    db.insert_scene(&scene(first + 1, 300, &a)).await.unwrap();
    assert_eq!(db.running_of("ada").await.unwrap(), (2, 900));
    let rows = db.workers().await.unwrap();
    assert_eq!((rows[0].scenes, rows[0].particles), (2, 900));
    assert_eq!(db.heartbeat(&a, "[]").await.unwrap(), Some(false));

    // b evicts a: a's scenes go, paused, one by one to the most free budget.
    assert!(db.evict(&a).await.unwrap());
    assert!(!db.evict(&a).await.unwrap(), "evicted once");
    let moved = db.place_orphans().await.unwrap();
    assert_eq!(moved.len(), 2);
    assert_eq!(moved[0], Moved { scene: first, to: c.clone() }, "c has the most free share");
    assert_eq!(moved[1].to, b, "then b: 0.7 left free against c's 0.55");
    let row = db.scene(first).await.unwrap().unwrap();
    assert_eq!((row.state.as_str(), row.lease.as_ref(), row.generation), ("paused", Some(&c), 1));
    assert_eq!(db.generation(first, Some(&c)).await.unwrap(), Some(1));

    // The late worker a: its heartbeat and every write for the moved scenes fail.
    assert_eq!(db.heartbeat(&a, "[]").await.unwrap(), None, "a learns it was evicted");
    assert_eq!(db.generation(first, Some(&a)).await.unwrap(), None);
    assert!(matches!(db.update_state(first, Some(&a), "running", 1.0).await, Err(DbError::Fenced(_))));
    assert!(matches!(db.update_tunables(first, Some(&a), "{}").await, Err(DbError::Fenced(_))));
    assert!(matches!(db.delete_scene(first, Some(&a)).await, Err(DbError::Fenced(_))));
    assert!(db.scene(first).await.unwrap().is_some(), "a fenced delete deletes nothing");
    assert_eq!(db.scene(first).await.unwrap().unwrap().state, "paused");
    db.update_state(first, Some(&c), "running", 2.0).await.unwrap();

    // a joins again: a new epoch, holding nothing.
    let a2 = db.register_worker(&info("a", 1000)).await.unwrap();
    assert!(a2.epoch > c.epoch && db.scenes_held(&a2).await.unwrap().is_empty());

    // c drains: its scene goes to the other worker with room, not to c itself.
    assert!(db.set_draining("c", true).await.unwrap());
    assert_eq!(db.heartbeat(&c, "[]").await.unwrap(), Some(true));
    let to = db.hand_over(&c, first, 600).await.unwrap().unwrap();
    assert_eq!(to, a2, "a2 is left 0.4 free, b 0.1");
    assert_eq!(db.hand_over(&c, first, 600).await.unwrap(), None, "c no longer holds it");
    assert!(!db.set_draining("nobody", true).await.unwrap());

    // A worker restarting under its name takes back its own scenes.
    let b2 = db.register_worker(&info("b", 1000)).await.unwrap();
    assert_eq!(db.scenes_held(&b2).await.unwrap().iter().map(|r| r.id).collect::<Vec<_>>(), [first + 1]);
    assert!(matches!(db.update_state(first + 1, Some(&b), "paused", 0.0).await, Err(DbError::Fenced(_))));
    db.close().await;
}

/// Placements made one after another before any scene's row exists spread, as
/// simultaneous creations through several workers do; a creation that followed
/// its placement takes the room reserved for it; a row takes its reservation's
/// place; a reservation whose scene never comes lapses after its worker's beats.
#[tokio::test]
async fn placements_reserve_room_until_their_scene_arrives() {
    let dir = tempfile::tempdir().unwrap();
    let db = Database::open(&format!("sqlite://{}?mode=rwc", dir.path().join("r.db").display())).await.unwrap();
    let a = db.register_worker(&info("a", 1000)).await.unwrap();
    db.register_worker(&info("b", 1000)).await.unwrap();
    let on = |w: &str| Placement::On(w.into());
    assert_eq!(db.place(400, None, None).await.unwrap(), on("a"), "equal: the first name");
    assert_eq!(db.place(400, None, None).await.unwrap(), on("b"), "a's room is reserved");
    assert_eq!(db.place(400, None, None).await.unwrap(), on("a"));
    assert_eq!(db.place(400, None, None).await.unwrap(), on("b"));
    let full = db.place(400, None, None).await.unwrap();
    assert!(
        matches!(&full, Placement::Refused(why) if why.contains("b has 200 of its 1000 particles free")),
        "{full:?}"
    );
    // The creation that followed its placement to b: room waits there.
    assert_eq!(db.place(400, Some("b"), None).await.unwrap(), on("b"));
    assert_eq!(db.place(10, None, Some("gpu")).await.unwrap(), Placement::Unserved("cpu".into()));
    // Its row takes the reservation's place: a's room stays as it was.
    let id = db.take_scene_id().await.unwrap();
    db.insert_scene(&scene(id, 400, &a)).await.unwrap();
    let rows = db.workers().await.unwrap();
    assert_eq!((rows[0].scenes, rows[0].particles, rows[0].reserved), (1, 400, (1, 400)));
    // A reservation lapses after RESERVED_BEATS of its worker's heartbeats.
    for _ in 0..RESERVED_BEATS {
        db.heartbeat(&a, "[]").await.unwrap();
    }
    let rows = db.workers().await.unwrap();
    assert_eq!((rows[0].reserved, rows[1].reserved), ((0, 0), (2, 800)));
    assert_eq!(db.place(600, None, None).await.unwrap(), on("a"));
    db.close().await;
}
