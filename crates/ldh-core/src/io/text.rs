//! The reader's text layer (SPEC §2): bytes to numbered lines, lines to fields, cells to
//! numbers. Empty, binary, UTF-16 and non-UTF-8 content is refused here with the file and the
//! byte offset or line; a cell that is not a number with its line and column.

use std::path::Path;

use super::format::Decimal;
use super::reader::reserve;
use crate::error::{LdhError, Location, Result};

/// Refuse empty, binary and non-UTF-8 content; strip a BOM.
pub(super) fn decode_text<'a>(bytes: &'a [u8], path: &Path) -> Result<&'a str> {
    if bytes.is_empty() {
        return Err(LdhError::EmptyFile {
            path: path.to_path_buf(),
        });
    }
    let body = bytes.strip_prefix(&[0xEF, 0xBB, 0xBF]).unwrap_or(bytes);
    // UTF-16 (byte-order mark, or every other byte zero in the first line's ASCII text): a
    // common export mistake, named as such rather than as a binary file.
    if let Some(big_endian) = utf16_order(bytes) {
        return Err(LdhError::Utf16 {
            path: path.to_path_buf(),
            big_endian,
        });
    }
    if let Some(off) = body
        .iter()
        .take(1 << 16)
        .position(|&b| b == 0 || (b < 0x09) || (0x0E..0x20).contains(&b) && b != 0x1B)
    {
        return Err(LdhError::Binary {
            path: path.to_path_buf(),
            offset: off as u64 + (bytes.len() - body.len()) as u64,
            byte: body[off],
        });
    }
    std::str::from_utf8(body).map_err(|e| {
        let off = e.valid_up_to();
        let line = body[..off].iter().filter(|&&b| b == b'\n').count() as u64 + 1;
        LdhError::NotUtf8 {
            loc: Location::line(path, line),
            offset: off as u64 + (bytes.len() - body.len()) as u64,
        }
    })
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

/// Number of lines of `bytes` (newlines, plus one for a last line without one).
fn bytecount_lines(bytes: &[u8]) -> usize {
    bytes.iter().filter(|&&b| b == b'\n').count() + usize::from(!bytes.ends_with(b"\n"))
}

/// The lines of `text` (decoded from `bytes`) with their 1-based numbers, a trailing `\r`
/// removed. Borrowed from `text`, no copy. The buffer, sized from the input, is reserved
/// fallibly: a file too large for the memory is this file's [`LdhError::OutOfMemory`], not an
/// abort.
pub(super) fn numbered_lines<'a>(
    bytes: &[u8],
    text: &'a str,
    path: &Path,
) -> Result<Vec<(u64, &'a str)>> {
    let n_lines = bytecount_lines(bytes);
    let mut lines: Vec<(u64, &str)> = Vec::new();
    reserve(&mut lines, n_lines, path)?;
    lines.extend(
        text.lines()
            .enumerate()
            .map(|(i, l)| (i as u64 + 1, l.strip_suffix('\r').unwrap_or(l))),
    );
    Ok(lines)
}

/// The most frequent of `,` `;` tab in a header line (ties: tab, `;`, `,`).
pub(super) fn detect_delimiter(line: &str) -> u8 {
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
/// exact file line numbers for messages while skipping comment lines anywhere in the file.
pub(super) fn split_fields<'a>(line: &'a str, delim: u8, out: &mut Vec<&'a str>) {
    out.clear();
    for f in line.split(delim as char) {
        let f = f.trim();
        let f = f
            .strip_prefix('"')
            .and_then(|x| x.strip_suffix('"'))
            .unwrap_or(f)
            .trim();
        out.push(f);
    }
}

/// Where a cell is, for messages: the file, the 1-based line, the 0-based column and its name.
pub(super) struct CellAt<'a> {
    /// The file.
    pub path: &'a Path,
    /// 1-based line.
    pub line: u64,
    /// 0-based column (messages print it 1-based).
    pub col: usize,
    /// The column's header name.
    pub name: &'a str,
}

/// One numeric cell as a finite number, with the `decimal` separator of the format. Refused:
/// Inf/NaN ([`LdhError::NonFinite`]) and text ([`LdhError::NotANumber`], with a hint for an
/// empty cell or a decimal comma when `delim` is not a comma).
pub(super) fn parse_number(cell: &str, decimal: Decimal, delim: u8, at: &CellAt) -> Result<f64> {
    let owned;
    let s = if decimal == Decimal::Comma {
        owned = cell.replace(',', ".");
        owned.as_str()
    } else {
        cell
    };
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(LdhError::NonFinite {
            loc: Location::cell(at.path, at.line, at.col + 1),
            column: at.name.to_string(),
            value: cell.to_string(),
        }),
        Err(_) => {
            let hint = if cell.is_empty() {
                "; the cell is empty".to_string()
            } else if decimal == Decimal::Point
                && delim != b','
                && cell.contains(',')
                && cell.replace(',', ".").parse::<f64>().is_ok()
            {
                "; this looks like a decimal comma: set decimal = \",\" in the format".to_string()
            } else {
                String::new()
            };
            Err(LdhError::NotANumber {
                loc: Location::cell(at.path, at.line, at.col + 1),
                column: at.name.to_string(),
                value: cell.chars().take(60).collect(),
                hint,
            })
        }
    }
}
