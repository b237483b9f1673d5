//! Byte-level mutations, for either format: truncation anywhere (also inside a UTF-8
//! character), stray bytes (NUL, invalid UTF-8, a byte-order mark, control characters,
//! markup), deleted and duplicated ranges, and CRLF line ends.

use rand::Rng;
use rand_chacha::ChaCha8Rng;

use super::{pick, Applied};

/// Stray byte sequences: NUL, bytes that are never UTF-8, a truncated and an overlong
/// sequence, a lone surrogate's encoding, a byte-order mark, control characters and syntax.
const STRAY: &[&[u8]] = &[
    b"\0",
    b"\xff",
    b"\xfe\xff",
    b"\xc3",
    b"\xc0\x80",
    b"\xed\xa0\x80",
    b"\xef\xbb\xbf",
    b"\r",
    b"\x1b[0m",
    b"\x0b\x0c",
    b"<",
    b">",
    b"&",
    b"\"",
    b"'",
    b"[",
    b"]",
    b"{",
    b"}",
    b"=",
    b"#",
    b"\\",
    b"\n\n[[",
    b"\xe2\x80\xae",
];

/// Applies one random byte-level mutation to `bytes`.
pub fn mutate(rng: &mut ChaCha8Rng, bytes: &mut Vec<u8>) -> Applied {
    let len = bytes.len();
    match rng.gen_range(0..6) {
        0 => {
            let at = rng.gen_range(0..=len);
            bytes.truncate(at);
            Applied::anywhere(format!("truncate at byte {at}"))
        }
        1 => {
            let at = rng.gen_range(0..=len);
            let stray = *pick(rng, STRAY);
            bytes.splice(at..at, stray.iter().copied());
            Applied::anywhere(format!("insert {stray:?} at byte {at}"))
        }
        2 => {
            let at = rng.gen_range(0..=len);
            let byte: u8 = rng.gen();
            bytes.insert(at, byte);
            Applied::anywhere(format!("insert byte {byte:#04x} at byte {at}"))
        }
        3 => {
            let (start, end) = range(rng, len);
            bytes.drain(start..end);
            Applied::anywhere(format!("delete bytes {start}..{end}"))
        }
        4 => {
            let (start, end) = range(rng, len);
            let copy = bytes[start..end].to_vec();
            bytes.splice(end..end, copy);
            Applied::anywhere(format!("duplicate bytes {start}..{end}"))
        }
        _ => {
            let crlf = bytes.iter().fold(Vec::with_capacity(len), |mut out, &b| {
                if b == b'\n' {
                    out.push(b'\r');
                }
                out.push(b);
                out
            });
            *bytes = crlf;
            Applied::anywhere("CRLF line ends")
        }
    }
}

/// A random range of at most 64 bytes within `len`.
fn range(rng: &mut ChaCha8Rng, len: usize) -> (usize, usize) {
    let start = rng.gen_range(0..=len);
    let end = (start + rng.gen_range(0..=64)).min(len);
    (start, end)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn mutations_are_seeded_and_change_the_bytes() {
        let text = b"name = \"a\"\n[[link]]\nname = \"b\"\n".to_vec();
        let mut changed = 0;
        for seed in 0..64 {
            let run = |seed| {
                let mut bytes = text.clone();
                let applied = mutate(&mut ChaCha8Rng::seed_from_u64(seed), &mut bytes);
                (bytes, applied)
            };
            assert_eq!(run(seed), run(seed));
            changed += usize::from(run(seed).0 != text);
        }
        assert!(changed > 48, "{changed}");
    }
}
