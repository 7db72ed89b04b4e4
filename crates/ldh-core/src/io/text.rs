//! The reader's text layer (SPEC §2): a byte stream to numbered lines, read one at a time
//! ([`Lines`]), lines to fields (cells to numbers: [`super::number`]). Empty, binary, UTF-16 and non-UTF-8 content
//! is refused here with the file and the line and byte offset; a NUL byte anywhere with its
//! line; a cell that is not a number with its line and column.
//!
//! Streaming: only the current line is held (at most [`MAX_LINE_BYTES`]: a longer line is
//! refused with its file and line, before more of it is read), so reading takes memory for the
//! columns kept, not for the file. The first 64 KiB are checked as a whole before any line is parsed (binary
//! bytes, UTF-16, UTF-8): in a small file a text-level fault is reported before any other, as
//! when the whole file was decoded first; further on, the first fault in file order is.

use std::io::{BufRead, Read};
use std::path::Path;

use super::MAX_LINE_BYTES;
use crate::error::{LdhError, Location, Result};

/// Bytes checked as a whole before parsing: binary bytes, UTF-16 and UTF-8 validity.
const HEAD_BYTES: usize = 1 << 16;

/// The lines of a byte stream, numbered from 1, read one at a time: a trailing `\n`, `\r\n`
/// and one more `\r` removed, a NUL byte and invalid UTF-8 refused with the line, a UTF-8
/// byte-order mark skipped, a line longer than [`MAX_LINE_BYTES`] refused, and the bytes
/// counted against the file-size limit.
pub(crate) struct Lines<'p, R> {
    src: std::io::Chain<std::io::Cursor<Vec<u8>>, R>,
    buf: Vec<u8>,
    path: &'p Path,
    /// Number of the line in `buf` (0 before the first).
    lineno: u64,
    /// Bytes consumed, BOM included (the file offset of the next line).
    offset: u64,
    /// The size limit in bytes and in MB as given (for [`LdhError::FileTooLarge`]).
    limit: Option<(u64, f64)>,
    /// A UTF-8 byte-order mark was found.
    pub bom: bool,
}

impl<'p, R: BufRead> Lines<'p, R> {
    /// Start reading `src` (the content of `path`): the first 64 KiB are read and checked —
    /// empty, UTF-16, binary bytes, invalid UTF-8 — and a BOM is skipped. `limit_mb`: refuse
    /// the content once it exceeds this many MB (10^6 bytes).
    pub fn new(mut src: R, path: &'p Path, limit_mb: Option<f64>) -> Result<Self> {
        let io = |source| LdhError::Io {
            path: path.to_path_buf(),
            source,
        };
        let mut head = Vec::new();
        (&mut src)
            .take(HEAD_BYTES as u64 + 3)
            .read_to_end(&mut head)
            .map_err(io)?;
        let more = !src.fill_buf().map_err(io)?.is_empty();
        check_head(&head, more, path)?;
        let bom = head.starts_with(&[0xEF, 0xBB, 0xBF]);
        let mut cursor = std::io::Cursor::new(head);
        if bom {
            cursor.set_position(3);
        }
        Ok(Lines {
            src: cursor.chain(src),
            buf: Vec::new(),
            path,
            lineno: 0,
            offset: if bom { 3 } else { 0 },
            limit: limit_mb.map(|mb| ((mb * 1e6) as u64, mb)),
            bom,
        })
    }

    /// The raw bytes of the next line, newline included (empty at the end); counted. A line
    /// longer than [`MAX_LINE_BYTES`] is refused once that much of it is read
    /// ([`LdhError::LineTooLong`]): no more is ever held.
    fn next_raw(&mut self) -> Result<u64> {
        self.buf.clear();
        let n = (&mut self.src)
            .take(MAX_LINE_BYTES as u64 + 1)
            .read_until(b'\n', &mut self.buf)
            .map_err(|source| LdhError::Io {
                path: self.path.to_path_buf(),
                source,
            })?;
        if n > MAX_LINE_BYTES {
            return Err(LdhError::LineTooLong {
                loc: Location::line(self.path, self.lineno + 1),
                limit_bytes: MAX_LINE_BYTES,
            });
        }
        let start = self.offset;
        self.offset += n as u64;
        if let Some((limit, limit_mb)) = self.limit {
            if self.offset > limit {
                return Err(LdhError::FileTooLarge {
                    path: self.path.to_path_buf(),
                    size_mb: self.offset as f64 / 1e6,
                    limit_mb,
                });
            }
        }
        if n > 0 {
            self.lineno += 1;
        }
        Ok(start)
    }

    /// The next line (1-based number, text without its line ending), `None` at the end.
    pub fn next_line(&mut self) -> Result<Option<(u64, &str)>> {
        let start = self.next_raw()?;
        if self.buf.is_empty() {
            return Ok(None);
        }
        // `contains` on bytes is a memchr; the position only when there is one.
        if let Some(p) = self
            .buf
            .contains(&0)
            .then(|| self.buf.iter().position(|&b| b == 0))
            .flatten()
        {
            return Err(LdhError::Binary {
                loc: Location::line(self.path, self.lineno),
                offset: start + p as u64,
                byte: 0,
            });
        }
        let mut line = &self.buf[..];
        if let Some(l) = line.strip_suffix(b"\n") {
            line = l.strip_suffix(b"\r").unwrap_or(l);
        }
        line = line.strip_suffix(b"\r").unwrap_or(line);
        match std::str::from_utf8(line) {
            Ok(s) => Ok(Some((self.lineno, s))),
            Err(e) => Err(LdhError::NotUtf8 {
                loc: Location::line(self.path, self.lineno),
                offset: start + e.valid_up_to() as u64,
            }),
        }
    }

    /// Whether every line left is blank (whitespace only); reads them all.
    pub fn rest_is_blank(&mut self) -> Result<bool> {
        loop {
            self.next_raw()?;
            if self.buf.is_empty() {
                return Ok(true);
            }
            if !String::from_utf8_lossy(&self.buf).trim().is_empty() {
                return Ok(false);
            }
        }
    }

    /// The number of lines left that are neither blank nor start (after blanks) with one of
    /// `comment_prefixes`: the data rows left, counted without parsing them.
    pub fn count_rows_left(&mut self, comment_prefixes: &[String]) -> Result<u64> {
        let mut n = 0;
        loop {
            self.next_raw()?;
            if self.buf.is_empty() {
                return Ok(n);
            }
            let t = self.buf.trim_ascii();
            if !t.is_empty() && !comment_prefixes.iter().any(|p| t.starts_with(p.as_bytes())) {
                n += 1;
            }
        }
    }
}

/// Refuse empty, UTF-16, binary and non-UTF-8 content in the first bytes of a file (`head`, up
/// to 64 KiB after a BOM; `more`: the file goes on), with the line and byte offset.
fn check_head(head: &[u8], more: bool, path: &Path) -> Result<()> {
    if head.is_empty() {
        return Err(LdhError::EmptyFile {
            path: path.to_path_buf(),
        });
    }
    let body = head.strip_prefix(&[0xEF, 0xBB, 0xBF]).unwrap_or(head);
    let bom_len = (head.len() - body.len()) as u64;
    let more = more || body.len() > HEAD_BYTES;
    let body = &body[..body.len().min(HEAD_BYTES)];
    // UTF-16 (byte-order mark, or every other byte zero in the first line's ASCII text): a
    // common export mistake, named as such rather than as a binary file.
    if let Some(big_endian) = utf16_order(head) {
        return Err(LdhError::Utf16 {
            path: path.to_path_buf(),
            big_endian,
        });
    }
    let line_at = |off: usize| body[..off].iter().filter(|&&b| b == b'\n').count() as u64 + 1;
    let binary = |b: u8| b == 0 || (b < 0x09) || (0x0E..0x20).contains(&b) && b != 0x1B;
    // Text has no control byte but tab, LF and CR: checked in blocks without an exit per byte
    // (it vectorises), the binary byte searched only when a block has another.
    let suspect = |c: &[u8]| {
        c.iter().fold(false, |any, &b| {
            any | (b < 0x20 && b != b'\t' && b != b'\n' && b != b'\r')
        })
    };
    let found = if body.chunks(256).any(suspect) {
        body.iter().position(|&b| binary(b))
    } else {
        None
    };
    if let Some(off) = found {
        return Err(LdhError::Binary {
            loc: Location::line(path, line_at(off)),
            offset: off as u64 + bom_len,
            byte: body[off],
        });
    }
    match std::str::from_utf8(body) {
        // A character cut by the end of the head is checked with its line.
        Err(e) if !(more && e.error_len().is_none()) => {
            let off = e.valid_up_to();
            Err(LdhError::NotUtf8 {
                loc: Location::line(path, line_at(off)),
                offset: off as u64 + bom_len,
            })
        }
        _ => Ok(()),
    }
}

/// `Some(big_endian)` when `bytes` look like UTF-16: a byte-order mark, or (without one) the
/// first up to 64 bytes alternate ASCII characters and zero bytes.
fn utf16_order(bytes: &[u8]) -> Option<bool> {
    if bytes.starts_with(&[0xFF, 0xFE]) {
        return Some(false);
    }
    if bytes.starts_with(&[0xFE, 0xFF]) {
        return Some(true);
    }
    let head = &bytes[..bytes.len().min(64) & !1];
    if head.len() < 4 {
        return None;
    }
    let ascii = |b: &u8| (0x09..0x7F).contains(b);
    let pairs = || head.chunks_exact(2);
    if pairs().all(|p| ascii(&p[0]) && p[1] == 0) {
        Some(false)
    } else if pairs().all(|p| p[0] == 0 && ascii(&p[1])) {
        Some(true)
    } else {
        None
    }
}

/// The most frequent of `,` `;` tab in a header line (ties: tab, `;`, `,`).
pub(crate) fn detect_delimiter(line: &str) -> u8 {
    let count = |c: char| line.chars().filter(|&x| x == c).count();
    let (t, s, c) = (count('\t'), count(';'), count(','));
    if t >= s && t >= c && t > 0 {
        b'\t'
    } else if s >= c && s > 0 {
        b';'
    } else {
        b','
    }
}

/// The fields of a header line, owned (see [`split_fields`]).
pub(super) fn split_header(line: &str, delim: u8) -> Vec<String> {
    let mut v = Vec::new();
    split_fields(line, delim, &mut v);
    v.into_iter().map(|s| s.to_string()).collect()
}

/// Split one line into trimmed fields, removing surrounding double quotes; `out` is cleared
/// first and reused from row to row.
///
/// Hand-written rather than the `csv` crate: rows are numeric, and per-line splitting keeps the
/// exact file line numbers for messages while skipping comment lines anywhere in the file. The
/// delimiters are ASCII bytes, which never occur inside a multi-byte UTF-8 character, so the
/// line is cut at those bytes by a plain scan (a `str::split` by `char` searched for each
/// field anew: ≈ 10 % of reading a 30 s leg, issue 17).
pub(super) fn split_fields<'a>(line: &'a str, delim: u8, out: &mut Vec<&'a str>) {
    out.clear();
    if !delim.is_ascii() {
        out.extend(line.split(delim as char).map(clean_field));
        return;
    }
    let mut start = 0;
    for (i, &b) in line.as_bytes().iter().enumerate() {
        if b == delim {
            out.push(clean_field(&line[start..i]));
            start = i + 1;
        }
    }
    out.push(clean_field(&line[start..]));
}

/// A field trimmed, then without surrounding double quotes, trimmed again. A field that starts
/// with a visible ASCII character other than `"` and ends with a visible ASCII character (a
/// number) has nothing to remove and is returned as it is.
fn clean_field(f: &str) -> &str {
    if let (Some(&a), Some(&z)) = (f.as_bytes().first(), f.as_bytes().last()) {
        if a.is_ascii_graphic() && a != b'"' && z.is_ascii_graphic() {
            return f;
        }
    }
    let f = f.trim();
    f.strip_prefix('"')
        .and_then(|x| x.strip_suffix('"'))
        .unwrap_or(f)
        .trim()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The byte scan splits and cleans fields as `str::split` + trim + unquote did.
    #[test]
    fn fields_are_split_as_by_str_split() {
        let old = |line: &str, d: u8| -> Vec<String> {
            line.split(d as char)
                .map(|f| {
                    let f = f.trim();
                    f.strip_prefix('"')
                        .and_then(|x| x.strip_suffix('"'))
                        .unwrap_or(f)
                        .trim()
                        .to_string()
                })
                .collect()
        };
        let mut out = Vec::new();
        for line in [
            "",
            "1,2,3",
            " 1 , 2,3 ",
            "\"a\",\" b \",\"c",
            "\"\",,\u{a0}4\u{a0},x\u{2003}",
            "é,ü;ß\t1",
            "1;2;3",
            "a\tb\t\"c\"\t",
            ",",
            "\"",
            "1.5,-2.25,\"3\"",
        ] {
            for d in [b',', b';', b'\t'] {
                split_fields(line, d, &mut out);
                let got: Vec<String> = out.iter().map(|s| s.to_string()).collect();
                assert_eq!(got, old(line, d), "{line:?} split by {:?}", d as char);
            }
        }
    }

    #[test]
    fn the_first_binary_byte_is_found_in_any_block() {
        let path = Path::new("f.csv");
        for at in [0usize, 5, 255, 256, 300, 4000] {
            for bad in [0u8, 1, 8, 0x0E, 0x1A, 0x1F] {
                let mut body = b"t,a\r\n1,\t2\n".repeat(500);
                body[at] = bad;
                match check_head(&body, false, path) {
                    Err(LdhError::Binary { offset, byte, .. }) => {
                        assert_eq!((offset, byte), (at as u64, bad));
                    }
                    other => panic!("{at} {bad}: {other:?}"),
                }
            }
        }
        // vertical tab, form feed and escape are text
        let body = b"t,a\x0b\x0c\x1b\n1,2\n".repeat(100);
        assert!(check_head(&body, false, path).is_ok());
    }
}
