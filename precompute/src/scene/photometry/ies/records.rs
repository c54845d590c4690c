//! The numeric data after `TILT=`, read as records of whole lines, every value with its line.

use super::Result;
use crate::scene::photometry::text::{words, File};

/// One value and its line.
#[derive(Clone, Copy)]
pub(super) struct Value<'a> {
    pub(super) line: usize,
    text: &'a str,
}

/// What follows the record being read, for telling a short record from a long one.
#[derive(Clone, Copy)]
pub(super) enum Next {
    /// A record of this many values.
    Size(usize),
    /// A record governed by the same count as this one (tilt angles, then their factors): if
    /// the count is wrong, the next record is as long as this one really is.
    Same,
    /// Nothing: the file's data ends.
    End,
    /// Not known yet.
    Unknown,
}

/// The numeric lines after `TILT=`, read as whole-line records.
pub(super) struct Records<'a> {
    pub(super) file: File<'a>,
    /// Lines that hold values, with their values.
    pub(super) lines: Vec<(usize, Vec<&'a str>)>,
    /// Index of the first line not read yet.
    pub(super) next: usize,
    /// The line an error names when the file ends before any value.
    before_data: usize,
}

impl<'a> Records<'a> {
    pub(super) fn new(file: File<'a>, lines: &[(usize, &'a str)], before_data: usize) -> Self {
        let lines = lines
            .iter()
            .map(|(n, l)| (*n, words(l).collect::<Vec<_>>()))
            .filter(|(_, w)| !w.is_empty())
            .collect();
        Records {
            file,
            lines,
            next: 0,
            before_data,
        }
    }

    /// The next record of `n` values, on whole lines.
    pub(super) fn record(&mut self, n: usize, what: &str, next: Next) -> Result<Vec<Value<'a>>> {
        let start = self.next;
        let (mut found, mut end) = (0, start);
        while found < n {
            let Some((_, values)) = self.lines.get(end) else {
                let line = if end > start {
                    self.lines[end - 1].0
                } else {
                    self.lines.last().map_or(self.before_data, |l| l.0)
                };
                return Err(self.file.count(line, what, n, found));
            };
            found += values.len();
            end += 1;
        }
        if found > n {
            let last = end - 1;
            let before = found - self.lines[last].1.len();
            // The record ends inside a line: either that line holds too many values, or the
            // record ended on the line before and this line starts the next record.
            let fits = match next {
                Next::Same => self.fits(last, n) || self.fits(last, before),
                Next::Size(size) => self.fits(last, size),
                Next::End | Next::Unknown => false,
            };
            if before > 0 && fits {
                return Err(self.file.count(self.lines[last - 1].0, what, n, before));
            }
            return Err(self.file.count(self.lines[last].0, what, n, found));
        }
        self.next = end;
        Ok(self.lines[start..end]
            .iter()
            .flat_map(|(line, values)| {
                values.iter().map(|t| Value {
                    line: *line,
                    text: t,
                })
            })
            .collect())
    }

    /// Whether a record of `size` values fills whole lines from line `from`.
    fn fits(&self, from: usize, size: usize) -> bool {
        let mut sum = 0;
        for (_, values) in &self.lines[from..] {
            sum += values.len();
            if sum >= size {
                return sum == size;
            }
        }
        false
    }

    /// No value may follow the last record.
    pub(super) fn finish(&self, counts_line: usize) -> Result<()> {
        let Some((line, _)) = self.lines.get(self.next) else {
            return Ok(());
        };
        let extra: usize = self.lines[self.next..].iter().map(|(_, v)| v.len()).sum();
        Err(self.file.invalid(
            *line,
            format!(
                "{extra} values follow the last candela record: the counts on line \
                 {counts_line} do not match the data"
            ),
        ))
    }

    pub(super) fn number(&self, v: Value, what: &str) -> Result<f64> {
        self.file.number(v.line, v.text, || what.to_string())
    }

    pub(super) fn integer(&self, v: Value, what: &str, min: i64, max: i64) -> Result<i64> {
        self.file
            .integer(v.line, v.text, min, max, || what.to_string())
    }
}

/// Angles that must be finite, strictly increasing and within `min..=max` degrees.
pub(super) fn increasing_angles(
    records: &Records,
    values: &[Value],
    what: &str,
    min: f64,
    max: f64,
) -> Result<Vec<f64>> {
    let mut angles: Vec<f64> = Vec::with_capacity(values.len());
    for (i, &v) in values.iter().enumerate() {
        let a = records.number(v, what)?;
        if !(min..=max).contains(&a) {
            return Err(records.file.invalid(
                v.line,
                format!("{what} {} is {a}°, outside {min}°…{max}°", i + 1),
            ));
        }
        if let Some(&before) = angles.last() {
            if a <= before {
                return Err(records.file.invalid(
                    v.line,
                    format!(
                        "{what} {} is {a}°, not above the one before ({before}°): angles must \
                         increase",
                        i + 1
                    ),
                ));
            }
        }
        angles.push(a);
    }
    Ok(angles)
}
