//! A [`Dataset`] from plain arrays (the Python binding's `X`, `y`, `groups`).

use ndarray::Array2;

use super::{Dataset, Task};
use crate::error::{LdhError, Result};

impl Dataset {
    /// Rows of `x` with labels `y`. `groups` (the subject of each row, for subject-grouped
    /// folds) defaults to every row its own subject (`row0`, `row1`…); `feature_names` to
    /// `x0`, `x1`…. Lengths that do not match `x` are refused, naming the argument.
    pub fn from_arrays(
        x: Array2<f64>,
        y: Vec<usize>,
        groups: Option<Vec<String>>,
        task: Task,
        feature_names: Option<Vec<String>>,
    ) -> Result<Dataset> {
        let (n, p) = x.dim();
        fn rows(what: &'static str, len: usize, of: &str) -> LdhError {
            LdhError::param(what, len, format!("X has {of}"))
        }
        if y.len() != n {
            return Err(rows("y", y.len(), &format!("{n} rows")));
        }
        let groups = groups.unwrap_or_else(|| (0..n).map(|i| format!("row{i}")).collect());
        if groups.len() != n {
            return Err(rows("groups", groups.len(), &format!("{n} rows")));
        }
        let names = feature_names.unwrap_or_else(|| (0..p).map(|j| format!("x{j}")).collect());
        if names.len() != p {
            return Err(rows("feature_names", names.len(), &format!("{p} columns")));
        }
        let ds = Dataset {
            task,
            feature_names: names,
            class_names: task.class_names(),
            x,
            y,
            row_ids: groups
                .iter()
                .enumerate()
                .map(|(i, g)| format!("{g}#{i}"))
                .collect(),
            groups,
            dropped: vec![],
        };
        ds.validate()?;
        Ok(ds)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_must_match_the_rows_and_columns() {
        let x = Array2::<f64>::zeros((4, 2));
        let e = Dataset::from_arrays(x.clone(), vec![0, 1], None, Task::Binary, None).unwrap_err();
        assert!(e.to_string().contains("X has 4 rows"), "{e}");
        let e = Dataset::from_arrays(
            x,
            vec![0, 1, 0, 1],
            None,
            Task::Binary,
            Some(vec!["a".into()]),
        )
        .unwrap_err();
        assert!(e.to_string().contains("feature_names"), "{e}");
    }
}
