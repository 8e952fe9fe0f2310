//! `floe admin`: users, API tokens and quota overrides, written straight to the
//! database (the same `--data-dir` / `--database` as `floe serve`). It works beside a
//! running server, which notices the change within a second.
//!
//! A new or rotated token is printed once, alone on stdout (so
//! `TOKEN=$(floe admin user add alice)` works); only its hash is stored.

use crate::auth::{token, valid_user_name};
use crate::cli::StoreArgs;
use crate::quota::Limit;
use crate::store::Database;
use clap::{Args, Subcommand};

/// `floe admin`.
#[derive(Debug, Args)]
pub struct AdminArgs {
    /// Where the server keeps its data.
    #[command(flatten)]
    pub store: StoreArgs,
    /// What to do.
    #[command(subcommand)]
    pub command: AdminCommand,
}

/// A `floe admin` command.
#[derive(Debug, Subcommand)]
pub enum AdminCommand {
    /// Users: add (prints their first token), list, remove.
    #[command(subcommand)]
    User(UserCommand),
    /// API tokens: rotate (revokes the old ones, prints a new one) or revoke.
    #[command(subcommand)]
    Token(TokenCommand),
    /// A user's quota overrides (the defaults are `floe serve --quota`).
    #[command(subcommand)]
    Quota(QuotaCommand),
    /// A cluster's workers: list them, drain one for maintenance (its scenes move to
    /// the others, paused, from a checkpoint taken then), or let it take scenes again.
    #[command(subcommand)]
    Worker(WorkerCommand),
}

/// `floe admin worker`.
#[derive(Debug, Subcommand)]
pub enum WorkerCommand {
    /// Every worker up, with its addresses, epoch, scenes and particles.
    List,
    /// Takes no new scenes and hands each of its scenes to another worker within a
    /// few seconds; stop it once `list` shows it holds none.
    Drain {
        /// Worker name.
        name: String,
    },
    /// Takes scenes again.
    Undrain {
        /// Worker name.
        name: String,
    },
}

/// `floe admin user`.
#[derive(Debug, Subcommand)]
pub enum UserCommand {
    /// Adds a user and prints their API token.
    Add {
        /// Login name: 1-64 of a-z 0-9 _ . - (starting with a letter or digit).
        name: String,
        /// May see every scene, call admin-only endpoints and read /metrics.
        #[arg(long)]
        admin: bool,
    },
    /// Lists the users with their token count and quota overrides.
    List,
    /// Removes a user and revokes their tokens (their scenes stay, for an admin).
    Remove {
        /// Login name.
        name: String,
    },
}

/// `floe admin token`.
#[derive(Debug, Subcommand)]
pub enum TokenCommand {
    /// Revokes a user's tokens and prints a new one.
    Rotate {
        /// Login name.
        name: String,
    },
    /// Revokes a user's tokens.
    Revoke {
        /// Login name.
        name: String,
    },
}

/// `floe admin quota`.
#[derive(Debug, Subcommand)]
pub enum QuotaCommand {
    /// Sets a user's quotas, e.g. `floe admin quota set alice running_scenes=4`.
    Set {
        /// Login name.
        name: String,
        /// NAME=VALUE, one or more.
        #[arg(required = true, value_parser = crate::quota::parse_assignment)]
        quotas: Vec<(Limit, u64)>,
    },
    /// Removes a user's overrides: the server's defaults apply again.
    Unset {
        /// Login name.
        name: String,
        /// Quota names, one or more.
        #[arg(required = true, value_parser = crate::quota::limit_named)]
        quotas: Vec<Limit>,
    },
}

/// Carries out `floe admin`.
pub fn admin(args: AdminArgs) -> anyhow::Result<()> {
    let runtime = tokio::runtime::Builder::new_current_thread().enable_all().build()?;
    runtime.block_on(async {
        let db = args.store.location().open_database().await?;
        let result = run(&db, args.command).await;
        db.close().await;
        result
    })
}

/// Adds a user; returns their first API token.
pub async fn add_user(db: &Database, name: &str, admin: bool) -> anyhow::Result<String> {
    if !valid_user_name(name) {
        anyhow::bail!(
            "'{}' cannot name a user: use 1-64 of a-z 0-9 _ . - starting with a letter or digit",
            crate::echo::cap(name)
        );
    }
    db.add_user(name, admin).await?;
    rotate_token(db, name).await
}

/// Revokes a user's tokens; returns a new one.
pub async fn rotate_token(db: &Database, name: &str) -> anyhow::Result<String> {
    let t = token::generate(token::API_PREFIX);
    db.replace_tokens(name, Some(&token::hash(&t))).await?;
    Ok(t)
}

async fn run(db: &Database, command: AdminCommand) -> anyhow::Result<()> {
    match command {
        AdminCommand::User(UserCommand::Add { name, admin }) => {
            let t = add_user(db, &name, admin).await?;
            eprintln!(
                "added {}user {name}; their API token (shown once, keep it secret):",
                if admin { "admin " } else { "" }
            );
            println!("{t}");
        }
        AdminCommand::User(UserCommand::List) => {
            let d = db.directory().await?;
            println!("{:<24} {:<6} {:>6}  quota overrides", "user", "admin", "tokens");
            for u in &d.users {
                let tokens = d.tokens.iter().filter(|t| t.1 == u.name).count();
                let quotas: Vec<String> =
                    d.quotas.iter().filter(|q| q.0 == u.name).map(|q| format!("{}={}", q.1, q.2)).collect();
                println!("{:<24} {:<6} {tokens:>6}  {}", u.name, if u.admin { "yes" } else { "no" }, quotas.join(" "));
            }
        }
        AdminCommand::User(UserCommand::Remove { name }) => {
            db.remove_user(&name).await?;
            let left = db.scenes().await?.iter().filter(|s| s.owner == name).count();
            eprintln!(
                "removed user {name} and their tokens; {left} of their scenes remain for an admin to keep or delete"
            );
        }
        AdminCommand::Token(TokenCommand::Rotate { name }) => {
            let t = rotate_token(db, &name).await?;
            eprintln!("revoked {name}'s tokens; the new one (shown once, keep it secret):");
            println!("{t}");
        }
        AdminCommand::Token(TokenCommand::Revoke { name }) => {
            db.replace_tokens(&name, None).await?;
            eprintln!("revoked {name}'s tokens");
        }
        AdminCommand::Quota(QuotaCommand::Set { name, quotas }) => {
            for (limit, value) in quotas {
                db.set_quota(&name, limit.name(), Some(value as i64)).await?;
                eprintln!("{name}: {}={value}", limit.name());
            }
        }
        AdminCommand::Worker(WorkerCommand::List) => {
            println!(
                "{:<16} {:>6} {:>7} {:>12} {:<9} {:<22} http",
                "worker", "epoch", "scenes", "particles", "state", "grpc"
            );
            for w in db.workers().await? {
                let particles = format!("{}/{}", w.particles, w.info.max_particles);
                let state = if w.draining { "draining" } else { "up" };
                println!(
                    "{:<16} {:>6} {:>7} {particles:>12} {state:<9} {:<22} {}",
                    w.info.name, w.epoch, w.scenes, w.info.grpc, w.info.http
                );
            }
        }
        AdminCommand::Worker(WorkerCommand::Drain { name }) => {
            anyhow::ensure!(db.set_draining(&name, true).await?, "no worker named '{}' is up", crate::echo::cap(&name));
            eprintln!(
                "{name} drains: it hands its scenes to the other workers; stop it once `floe admin worker list` shows 0 scenes"
            );
        }
        AdminCommand::Worker(WorkerCommand::Undrain { name }) => {
            anyhow::ensure!(
                db.set_draining(&name, false).await?,
                "no worker named '{}' is up",
                crate::echo::cap(&name)
            );
            eprintln!("{name} takes scenes again");
        }
        AdminCommand::Quota(QuotaCommand::Unset { name, quotas }) => {
            for limit in quotas {
                db.set_quota(&name, limit.name(), None).await?;
                eprintln!("{name}: {} back to the server's default", limit.name());
            }
        }
    }
    Ok(())
}
