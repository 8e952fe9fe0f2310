//! API tokens and share-link tokens: 256 random bits, hex, behind a prefix that
//! names what they are (`floe_pat_` for a user's API token, `floe_shr_` for a
//! read-only share link), so a leaked one is recognisable in a log or by a secret
//! scanner.
//!
//! Only a token's SHA-256 is stored. A fast hash is enough here: the token is
//! 256 uniformly random bits, so there is no dictionary to try and a slow,
//! salted password hash (argon2, bcrypt) would only slow every request down.
//! Lookups go by hash, so the time a lookup takes says nothing about the token.

use sha2::{Digest, Sha256};

/// Prefix of a user's API token.
pub const API_PREFIX: &str = "floe_pat_";
/// Prefix of a share link's token.
pub const SHARE_PREFIX: &str = "floe_shr_";
/// Hex digits after the prefix.
const HEX_LEN: usize = 64;
/// Hex digits of a token's hash that name a share link (to list and revoke it).
pub const SHARE_ID_LEN: usize = 12;

/// A new random token with `prefix`.
pub fn generate(prefix: &str) -> String {
    let mut bytes = [0u8; 32];
    getrandom::fill(&mut bytes).expect("the operating system's random number generator");
    format!("{prefix}{}", hex(&bytes))
}

/// The stored form of a token: SHA-256, hex.
pub fn hash(token: &str) -> String {
    hex(&Sha256::digest(token.as_bytes()))
}

/// Whether `text` has the shape of a token with `prefix` (checked before hashing, so a
/// mistyped credential gets a precise message).
pub fn well_formed(text: &str, prefix: &str) -> bool {
    text.strip_prefix(prefix)
        .is_some_and(|h| h.len() == HEX_LEN && h.bytes().all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b)))
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_are_random_prefixed_and_hashed() {
        let a = generate(API_PREFIX);
        let b = generate(API_PREFIX);
        assert_ne!(a, b);
        assert!(well_formed(&a, API_PREFIX), "{a}");
        assert!(!well_formed(&a, SHARE_PREFIX));
        assert!(!well_formed(&a[..a.len() - 1], API_PREFIX));
        assert!(!well_formed(&a.to_uppercase(), API_PREFIX));
        assert_eq!(hash("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    }
}
