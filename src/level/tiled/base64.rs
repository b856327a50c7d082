//! A tile layer's base64 data as the `tiled` crate decodes it, checked before it does: what is
//! not base64 (named at its character and line), how far compressed data inflates (read no
//! further than the layer's cells), and which cell first holds a gid the crate would drop.

use std::io::Read;

use super::scan::{Data, ScanError};

/// What is wrong with a layer's base64 data that [`base64_decode`] refused: the first
/// character outside the alphabet (whitespace inside the data included, which the crate does
/// not skip), or a length that is not a multiple of 4.
pub(super) fn not_base64(d: &Data) -> ScanError {
    let text = d.text.trim();
    let lead = d.text.len() - d.text.trim_start().len();
    let bad = text
        .char_indices()
        .find(|&(_, c)| !(c.is_ascii_alphanumeric() || c == '+' || c == '/' || c == '='));
    let early_pad = text
        .char_indices()
        .find(|&(at, c)| c == '=' && !text[at..].trim_start_matches('=').is_empty());
    let line_at = |at: usize| d.line + d.text[..lead + at].matches('\n').count();
    let (line, found) = match (bad, early_pad) {
        (Some((at, c)), _) => (line_at(at), format!("{c:?} at character {}", at + 1)),
        (None, _) if !text.len().is_multiple_of(4) => (
            d.line,
            format!("{} characters, not a multiple of 4", text.len()),
        ),
        (None, Some((at, _))) => (
            line_at(at),
            format!("'=' padding at character {} before its end", at + 1),
        ),
        (None, None) => (
            d.line,
            "a last character whose unused bits are not zero".to_string(),
        ),
    };
    ScanError {
        column: None,
        line,
        message: format!(
            "{}: its base64 data holds {found}; expected standard base64 (A-Z, a-z, 0-9, '+', '/', '=' padding) with no space or line break inside, as Tiled writes it",
            d.place
        ),
    }
}

/// How many bytes `r` gives (inflated, if it is a decoder), reading at most one byte more than
/// `expected` (so a small layer that inflates to gigabytes is found after `expected + 1`
/// bytes), the first cell (its index, and why, of gids read little-endian as the crate reads
/// them) that `bad` refuses, and why the stream broke off, if it did (a corrupt compressed stream).
pub(super) fn read_cells(
    r: impl Read,
    expected: u64,
    mut bad: impl FnMut(u32) -> Option<String>,
) -> (u64, Option<(u64, String)>, Option<std::io::Error>) {
    let mut counted = 0u64;
    let mut first_bad = None;
    let mut cell = [0u8; 4];
    let mut buf = [0u8; 8192];
    let mut r = r.take(expected + 1);
    loop {
        let n = match r.read(&mut buf) {
            Ok(0) => break,
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return (counted, first_bad, Some(e)),
        };
        for &b in &buf[..n] {
            cell[(counted % 4) as usize] = b;
            counted += 1;
            if counted.is_multiple_of(4) && first_bad.is_none() {
                let gid = u32::from_le_bytes(cell);
                first_bad = bad(gid).map(|why| (counted / 4 - 1, why));
            }
        }
    }
    (counted, first_bad, None)
}

/// Standard base64 with padding, whitespace ignored; `None` if it is not base64.
pub(super) fn base64_decode(text: &str) -> Option<Vec<u8>> {
    let value = |c: u8| -> Option<u32> {
        Some(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            _ => return None,
        } as u32)
    };
    let clean: Vec<u8> = text.bytes().filter(|b| !b.is_ascii_whitespace()).collect();
    if !clean.len().is_multiple_of(4) {
        return None;
    }
    let mut out = Vec::with_capacity(clean.len() / 4 * 3);
    for quad in clean.chunks_exact(4) {
        let pad = quad.iter().rev().take_while(|&&b| b == b'=').count();
        if pad > 2 {
            return None;
        }
        let mut acc = 0u32;
        for &b in &quad[..4 - pad] {
            acc = (acc << 6) | value(b)?;
        }
        acc <<= 6 * pad as u32;
        let bytes = acc.to_be_bytes();
        // Padding only at the end, and no bits left over before it (as the crate decodes).
        if pad > 0
            && (out.len() + 3 < clean.len() / 4 * 3 || bytes[4 - pad..].iter().any(|&b| b != 0))
        {
            return None;
        }
        out.extend_from_slice(&bytes[1..4 - pad]);
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_round_trips() {
        assert_eq!(base64_decode("AQAAAA==").unwrap(), vec![1, 0, 0, 0]);
        assert_eq!(base64_decode(" AQID\nBA== ").unwrap(), vec![1, 2, 3, 4]);
        assert_eq!(base64_decode("AQIDBAUG").unwrap(), vec![1, 2, 3, 4, 5, 6]);
        assert!(base64_decode("A").is_none());
        assert!(base64_decode("A*==").is_none());
    }

    #[test]
    fn cells_are_read_little_endian_and_the_first_bad_one_is_named() {
        let bytes = [0u8, 0, 0, 0, 7, 0, 0, 0, 1, 1, 0, 0, 9, 0, 0, 0];
        // Cell 1 holds gid 7, cell 2 gid 257: the first over 5 is cell 1.
        let over_5 = |g: u32| (g > 5).then(|| format!("gid {g}"));
        let (n, bad, broke) = read_cells(&bytes[..], 16, over_5);
        assert_eq!(
            (n, bad, broke.is_none()),
            (16, Some((1, "gid 7".into())), true)
        );
        assert_eq!(read_cells(&bytes[..], 16, |_| None).1, None);
        // Read no further than one byte past what the layer holds.
        assert_eq!(read_cells(&bytes[..], 8, |_| None).0, 9);
        // A zlib stream whose data is not deflate breaks off with an error.
        let corrupt = [0x78u8, 0x9c, 0xff, 0xff, 0xff, 0xff];
        let (_, _, broke) = read_cells(flate2::read::ZlibDecoder::new(&corrupt[..]), 16, |_| None);
        assert!(broke.is_some());
    }
}
