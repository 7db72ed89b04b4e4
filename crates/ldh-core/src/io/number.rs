//! Cells to numbers (SPEC §2): the reader's parse of one numeric cell, with a fast path for the
//! plain decimals loggers write (`[-]digits[.digits]`) that gives `str::parse`'s bits, and the
//! errors for a cell that is not a finite number (file, line, column, value).

use std::path::Path;

use super::format::Decimal;
use crate::error::{LdhError, Location, Result};

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

/// 10^0 … 10^15, each exactly representable.
const POW10: [f64; 16] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
];

/// `s.parse::<f64>()` of the common cell `[-]digits[.digits]` with at most 15 digits, else
/// `None` (the caller then parses it with the standard library, errors included).
///
/// Hand-written because it is the standard library's own exact fast path (Clinger 1990)
/// without its general grammar: the digits make an integer m < 10^15 < 2^53 and the point a
/// power 10^f with f ≤ 15, both exact in `f64`, so the one division m / 10^f is correctly
/// rounded — the value `str::parse` returns, which is correctly rounded for every input. A
/// float-parsing crate would accept another grammar (which cells are refused must not change)
/// and still need this check. The number parse was ≈ 40 % of reading a 30 s leg (issue 17).
pub(crate) fn parse_plain_decimal(s: &str) -> Option<f64> {
    let b = s.as_bytes();
    let (neg, body) = match b.first()? {
        b'-' => (true, &b[1..]),
        _ => (false, b),
    };
    if body.is_empty() || body.len() > 16 {
        return None;
    }
    if let Some(v) = short_plain_decimal(body) {
        return Some(if neg { -v } else { v });
    }
    // m: the digits as an integer; `point`: the index after the decimal point
    let (mut m, mut point) = (0u64, None);
    for (i, &c) in body.iter().enumerate() {
        let d = c.wrapping_sub(b'0');
        if d < 10 {
            m = m * 10 + u64::from(d);
        } else if c == b'.' && point.is_none() {
            point = Some(i + 1);
        } else {
            return None;
        }
    }
    let frac = point.map_or(0, |p| body.len() - p);
    let digits = body.len() - usize::from(point.is_some());
    if digits == 0 || digits > 15 {
        return None;
    }
    let v = m as f64 / POW10[frac];
    Some(if neg { -v } else { v })
}

/// [`parse_plain_decimal`] of an unsigned `body` of 4–8 bytes, all in one 64-bit word (SWAR,
/// as in Lemire's fast_float: the digits' value by three multiplications instead of one
/// dependent multiply-add per digit); `None` when it is not `digits[.digits]` (the caller's
/// byte loop then decides, as for every other cell). The same integer m and the same one
/// division, so the same bits (tested against `str::parse` with the loop's own test).
fn short_plain_decimal(body: &[u8]) -> Option<f64> {
    let len = body.len();
    if !(4..=8).contains(&len) {
        return None;
    }
    // the bytes in order from the lowest, by two overlapping 4-byte reads
    let lo = u64::from(u32::from_le_bytes(body[..4].try_into().ok()?));
    let hi = u64::from(u32::from_le_bytes(body[len - 4..].try_into().ok()?));
    let x = lo | hi << (8 * (len - 4));
    const ONES: u64 = 0x0101_0101_0101_0101;
    const ZEROS: u64 = 0x3030_3030_3030_3030;
    if x & (ONES * 0x80) != 0 {
        return None;
    }
    // right-aligned: '0' bytes (no value) before the first character
    let pad = 8 * (8 - len);
    let x = if pad == 0 {
        x
    } else {
        x << pad | (ZEROS >> (64 - pad))
    };
    // the point: the lowest byte equal to '.' (at most one may remain a non-digit)
    let dots = x ^ (ONES * u64::from(b'.'));
    let zero = dots.wrapping_sub(ONES) & !dots & (ONES * 0x80);
    let (digits, frac) = if zero == 0 {
        (x, 0)
    } else {
        let p = (zero.trailing_zeros() / 8) as usize;
        // drop byte p: the bytes below it move up one, a '0' comes in at the bottom
        let below = (1u64 << (8 * p)) - 1;
        let moved = ((x & below) << 8) | (x & !below & !(0xFF << (8 * p)));
        (moved | u64::from(b'0'), 7 - p)
    };
    // every byte a digit: high nibble 3 and no carry into it when adding 6
    let ok = (digits & (ONES * 0xF0)) == ZEROS
        && (digits.wrapping_add(ONES * 6) & (ONES * 0xF0)) == ZEROS;
    if !ok {
        return None;
    }
    // pairs, then fours, then the eight digits (the products wrap by design: only the bytes
    // and the half kept hold the value)
    let mut v = digits - ZEROS;
    v = v.wrapping_mul(10).wrapping_add(v >> 8);
    let m = ((v & 0x0000_00FF_0000_00FF)
        .wrapping_mul(0x000F_4240_0000_0064)
        .wrapping_add(((v >> 16) & 0x0000_00FF_0000_00FF).wrapping_mul(0x0000_2710_0000_0001)))
        >> 32;
    Some(m as f64 / POW10[frac])
}

/// One numeric cell as a finite number, with the `decimal` separator of the format. Refused:
/// Inf/NaN ([`LdhError::NonFinite`]) and text ([`LdhError::NotANumber`], with a hint for an
/// empty cell or a decimal comma when `delim` is not a comma).
pub(super) fn parse_number(cell: &str, decimal: Decimal, delim: u8, at: &CellAt) -> Result<f64> {
    if decimal == Decimal::Point || !cell.contains(',') {
        if let Some(v) = parse_plain_decimal(cell) {
            return Ok(v);
        }
    }
    parse_number_in_full(cell, decimal, delim, at)
}

/// [`parse_number`] beyond the plain decimals: decimal commas, the standard library's whole
/// grammar and the errors.
#[cold]
fn parse_number_in_full(cell: &str, decimal: Decimal, delim: u8, at: &CellAt) -> Result<f64> {
    // A decimal comma becomes a point in a stack buffer (no allocation per cell).
    let mut buf = [0u8; 64];
    let owned;
    let s = if decimal == Decimal::Comma && cell.contains(',') {
        if cell.len() <= buf.len() {
            let b = &mut buf[..cell.len()];
            for (o, &c) in b.iter_mut().zip(cell.as_bytes()) {
                *o = if c == b',' { b'.' } else { c };
            }
            // ASCII replaced by ASCII: still UTF-8.
            std::str::from_utf8(b).unwrap_or(cell)
        } else {
            owned = cell.replace(',', ".");
            owned.as_str()
        }
    } else {
        cell
    };
    if let Some(v) = parse_plain_decimal(s) {
        return Ok(v);
    }
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
                value: cell.to_string(),
                hint,
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The one-word path for 4–8 byte cells: every place of the point (or none), with and
    /// without a sign, random digits (leading zeros included), and a second point or another
    /// byte anywhere: `str::parse`'s bits, or no answer where it is not a plain decimal.
    #[test]
    fn short_cells_in_one_word_parse_to_the_standard_librarys_bits() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let others = b".-+eE x,";
        for len in 4..=8usize {
            for point in (0..=len).map(|p| (p < len).then_some(p)) {
                for t in 0..3000 {
                    let mut b: Vec<u8> = (0..len).map(|_| b'0' + rng.gen_range(0..10u8)).collect();
                    if let Some(p) = point {
                        b[p] = b'.';
                    }
                    if t % 5 == 0 {
                        b[rng.gen_range(0..len)] = others[rng.gen_range(0..others.len())];
                    }
                    let body = String::from_utf8(b).unwrap();
                    for s in [body.clone(), format!("-{body}")] {
                        match (parse_plain_decimal(&s), s.parse::<f64>()) {
                            (Some(v), Ok(w)) => assert_eq!(v.to_bits(), w.to_bits(), "{s:?}"),
                            (Some(v), Err(_)) => panic!("{s:?} answered {v}"),
                            (None, _) => {
                                let body = s.strip_prefix('-').unwrap_or(&s);
                                let plain = body.bytes().filter(|c| *c == b'.').count() <= 1
                                    && body.bytes().all(|c| c.is_ascii_digit() || c == b'.')
                                    && body.bytes().any(|c| c.is_ascii_digit());
                                assert!(!plain, "{s:?} not answered");
                            }
                        }
                    }
                }
            }
        }
    }

    /// The fast path gives `str::parse`'s bits whenever it answers, and answers for the plain
    /// decimals a logger writes.
    #[test]
    fn plain_decimals_parse_to_the_standard_librarys_bits() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let alphabet = b"0123456789.-+eE, x";
        let mut answered = 0;
        for t in 0..200_000 {
            let len = rng.gen_range(0..19);
            let s: String = (0..len)
                .map(|i| {
                    // mostly digits and one point, sometimes anything of the alphabet
                    if t % 4 == 0 || (i == 0 && rng.gen_bool(0.3)) {
                        alphabet[rng.gen_range(0..alphabet.len())] as char
                    } else if rng.gen_bool(0.1) {
                        '.'
                    } else {
                        (b'0' + rng.gen_range(0..10u8)) as char
                    }
                })
                .collect();
            if let Some(v) = parse_plain_decimal(&s) {
                answered += 1;
                let want = s.parse::<f64>().unwrap_or_else(|e| panic!("{s:?}: {e}"));
                assert_eq!(v.to_bits(), want.to_bits(), "{s:?}");
            }
        }
        assert!(answered > 50_000, "{answered}");
        let plain = [
            "0",
            "-0",
            "-0.000",
            "1.015",
            ".5",
            "5.",
            "-.25",
            "999999999999999",
            "0.1",
            "123456789012.345",
            "-0.458",
        ];
        for s in plain {
            let v = parse_plain_decimal(s).unwrap_or_else(|| panic!("{s} not answered"));
            assert_eq!(v.to_bits(), s.parse::<f64>().unwrap().to_bits(), "{s}");
        }
        // other grammar, more digits than are exact, and what is not a number: left to the
        // standard library (and its errors)
        for s in [
            "1e3",
            "+1",
            "-",
            ".",
            "",
            "1.2.3",
            "--1",
            "1,5",
            " 1",
            "1234567890123456",
            "NaN",
            "inf",
            "0x10",
            "1_0",
        ] {
            assert!(parse_plain_decimal(s).is_none(), "{s:?}");
        }
    }
}
