//! The checked axis map of a vendor format: a signed permutation from the file's sensor axes to
//! ldh's (x along the shank, y anterior-posterior, z medio-lateral), refused when malformed,
//! repeated or a reflection.

use super::FormatSpec;
use crate::error::Result;

/// The checked form of an axis map: ldh axis `i` = `sign[i]` × input axis `index[i]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisMap {
    /// Input axis index (0 = x, 1 = y, 2 = z) for each ldh axis.
    pub index: [usize; 3],
    /// Sign (+1 or −1) for each ldh axis.
    pub sign: [f64; 3],
}

impl AxisMap {
    /// The identity map.
    pub const IDENTITY: AxisMap = AxisMap {
        index: [0, 1, 2],
        sign: [1.0, 1.0, 1.0],
    };

    /// Apply to one sample.
    pub fn apply(&self, v: [f64; 3]) -> [f64; 3] {
        [
            self.sign[0] * v[self.index[0]],
            self.sign[1] * v[self.index[1]],
            self.sign[2] * v[self.index[2]],
        ]
    }

    /// The inverse map (ldh axes back to the file's axes).
    pub fn inverse(&self) -> AxisMap {
        let mut index = [0; 3];
        let mut sign = [1.0; 3];
        for (i, (&j, &s)) in self.index.iter().zip(self.sign.iter()).enumerate() {
            index[j] = i;
            sign[j] = s;
        }
        AxisMap { index, sign }
    }
}

impl FormatSpec {
    /// The checked axis map. Errors on a malformed entry, a repeated axis, or a reflection
    /// (determinant −1: both the sensor and ldh's frame are right-handed, so a reflection means
    /// a sign is wrong).
    pub fn axis_map(&self) -> Result<AxisMap> {
        let mut index = [0usize; 3];
        let mut sign = [1.0f64; 3];
        for (i, entry) in self.axes.map.iter().enumerate() {
            let e = entry.trim().to_ascii_lowercase();
            let (s, axis) = match e.as_bytes() {
                [b'+', a] => (1.0, *a),
                [b'-', a] => (-1.0, *a),
                [a] => (1.0, *a),
                _ => {
                    return Err(self.err(format!(
                        "axes.map entry '{entry}' is not like \"+x\" or \"-z\""
                    )))
                }
            };
            index[i] = match axis {
                b'x' => 0,
                b'y' => 1,
                b'z' => 2,
                _ => {
                    return Err(
                        self.err(format!("axes.map entry '{entry}' names no axis x, y or z"))
                    )
                }
            };
            sign[i] = s;
        }
        if index[0] == index[1] || index[0] == index[2] || index[1] == index[2] {
            return Err(self.err(format!("axes.map {:?} uses an axis twice", self.axes.map)));
        }
        // Determinant of a signed permutation = sign product × permutation parity.
        let parity = {
            let mut p = index;
            let mut swaps = 0;
            for i in 0..3 {
                while p[i] != i {
                    let j = p[i];
                    p.swap(i, j);
                    swaps += 1;
                }
            }
            if swaps % 2 == 0 {
                1.0
            } else {
                -1.0
            }
        };
        if parity * sign[0] * sign[1] * sign[2] < 0.0 {
            return Err(self.err(format!(
                "axes.map {:?} is a reflection (determinant −1); sensors are right-handed, so one sign is wrong",
                self.axes.map
            )));
        }
        Ok(AxisMap { index, sign })
    }
}
