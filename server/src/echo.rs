//! Error messages quote the request (a bad key, an unknown name, a syntax error's
//! line); a huge request must not make a huge message. gRPC carries the message in a
//! header, and standard clients refuse headers over 8-16 KiB: they would report a
//! metadata-size error instead of the answer. Every message a transport sends is
//! bounded here, keeping its start and end (where the field and the reason are).

/// Most bytes of an error message.
pub const MAX_MESSAGE_BYTES: usize = 1024;
/// Most bytes of a quoted piece of input inside a message.
pub const MAX_QUOTE_BYTES: usize = 128;

/// The largest char boundary of `s` at or below `at`.
fn floor(s: &str, mut at: usize) -> usize {
    while !s.is_char_boundary(at) {
        at -= 1;
    }
    at
}

/// The smallest char boundary of `s` at or above `at`.
fn ceil(s: &str, mut at: usize) -> usize {
    while !s.is_char_boundary(at) {
        at += 1;
    }
    at
}

/// `message` cut to at most [`MAX_MESSAGE_BYTES`] (plus the marker saying how much
/// was cut), keeping its first and last parts.
pub fn bounded(message: &str) -> String {
    if message.len() <= MAX_MESSAGE_BYTES {
        return message.to_owned();
    }
    let head = floor(message, MAX_MESSAGE_BYTES * 3 / 4);
    let tail = ceil(message, message.len() - MAX_MESSAGE_BYTES / 4);
    format!("{} … ({} bytes cut) … {}", &message[..head], tail - head, &message[tail..])
}

/// A piece of input to quote in a message, cut to at most [`MAX_QUOTE_BYTES`].
pub fn cap(input: &str) -> String {
    if input.len() <= MAX_QUOTE_BYTES {
        return input.to_owned();
    }
    let end = floor(input, MAX_QUOTE_BYTES);
    format!("{}… ({} bytes)", &input[..end], input.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_messages_keep_both_ends() {
        assert_eq!(bounded("short"), "short");
        let m = format!("override '{}': expected key=value", "é".repeat(100_000));
        let b = bounded(&m);
        assert!(b.len() < MAX_MESSAGE_BYTES + 64, "{}", b.len());
        assert!(b.starts_with("override 'é") && b.ends_with("': expected key=value"), "{b}");
        let q = cap(&"x".repeat(1000));
        assert!(q.starts_with("xxx") && q.ends_with("… (1000 bytes)") && q.len() < 150);
    }
}
