//! The operator as a flat list of numbers, for the form-factor cache (`crate::cache`): the
//! tree, the patches' order and areas, every block's span and numbers, and the compression
//! figures. Indices are stored as `f64` (exact below 2⁵³) and the f32 entries widened to `f64`
//! (exact), so that an operator read back is the one written, to the bit.
//!
//! Layout: `n`, the node count, per node its range (start, end) and children (−1 for a
//! leaf); the order (`n` patch indices); `√A` by patch (`n`); the block count, per block its
//! row and column nodes, its kind (0 near, 1 far), its rank (−1 for a dense block) and its
//! numbers (dense: `m × n` column-major; low rank: `U` then `V`); the figures of
//! [`Compression`] in their declaration order.
//!
//! Reading checks every index and length against the others, so that values that do not
//! describe an operator are an error rather than a panic later.

use super::tree::{BlockSpan, Kind};
use super::{Block, Compression, Data, Hierarchical};

impl Hierarchical {
    /// Appends the operator's numbers to `out` (module docs).
    pub(crate) fn write_values(&self, out: &mut Vec<f64>) {
        let index = |x: usize| x as f64;
        out.push(index(self.order.len()));
        out.push(index(self.nodes.len()));
        for (range, children) in &self.nodes {
            out.extend([index(range.start), index(range.end)]);
            match children {
                Some([l, r]) => out.extend([index(*l), index(*r)]),
                None => out.extend([-1.0, -1.0]),
            }
        }
        out.extend(self.order.iter().map(|&i| index(i)));
        out.extend_from_slice(&self.root_area);
        out.push(index(self.blocks.len()));
        for block in &self.blocks {
            let span = &block.span;
            out.extend([index(span.row_node), index(span.col_node)]);
            out.push(match span.kind {
                Kind::Near => 0.0,
                // A dark block is a far one of rank 0.
                Kind::Far | Kind::Clear | Kind::Dark | Kind::Shaded => 1.0,
            });
            match &block.data {
                Data::Dense(d) => {
                    out.push(-1.0);
                    out.extend(d.iter().map(|&x| f64::from(x)));
                }
                Data::LowRank { rank, u, v } => {
                    out.push(index(*rank));
                    out.extend(u.iter().chain(v).map(|&x| f64::from(x)));
                }
            }
        }
        let c = &self.compression;
        out.extend([
            index(c.near_blocks),
            index(c.low_rank_blocks),
            index(c.guard_fallbacks),
            index(c.rank_fallbacks),
            index(c.shaded_blocks),
            index(c.shade_splits),
            c.shade_misfit,
            index(c.max_rank),
            c.mean_rank,
            c.low_rank_share,
            c.entries_read,
            c.row_error,
        ]);
    }

    /// The operator over `n` patches from the numbers [`Hierarchical::write_values`] wrote, or
    /// what is wrong with them.
    pub(crate) fn read_values(values: &[f64], n: usize) -> Result<Hierarchical, String> {
        let mut r = Values { values, at: 0 };
        if r.index(usize::MAX)? != n {
            return Err("another number of patches".into());
        }
        // Each node takes four numbers: a count beyond what is left is no operator.
        let node_count = r.index(values.len() / 4)?;
        let mut nodes = Vec::with_capacity(node_count);
        for _ in 0..node_count {
            let (start, end) = (r.index(n)?, r.index(n)?);
            if start > end {
                return Err("a cluster ends before it starts".into());
            }
            let children = match (r.number()?, r.number()?) {
                (l, c) if l == -1.0 && c == -1.0 => None,
                (l, c) => {
                    let children = [r.checked(l, node_count - 1)?, r.checked(c, node_count - 1)?];
                    // The tree lists a node before its children: a walk down it ends.
                    if children.iter().any(|&child| child <= nodes.len()) {
                        return Err("a cluster's child listed before it".into());
                    }
                    Some(children)
                }
            };
            nodes.push((start..end, children));
        }
        let mut order = Vec::with_capacity(n);
        let mut position = vec![usize::MAX; n];
        for p in 0..n {
            let i = r.index(n.saturating_sub(1))?;
            if position[i] != usize::MAX {
                return Err("the order names a patch twice".into());
            }
            position[i] = p;
            order.push(i);
        }
        let root_area = r.take(n)?.to_vec();
        let block_count = r.index(values.len())?;
        let mut blocks = Vec::with_capacity(block_count.min(values.len()));
        for _ in 0..block_count {
            let last_node = node_count.checked_sub(1).ok_or("blocks without a tree")?;
            let (row_node, col_node) = (r.index(last_node)?, r.index(last_node)?);
            let kind = match r.number()? {
                0.0 => Kind::Near,
                1.0 => Kind::Far,
                _ => return Err("a block of no known kind".into()),
            };
            let span = BlockSpan {
                row_node,
                col_node,
                rows: nodes[row_node].0.clone(),
                cols: nodes[col_node].0.clone(),
                kind,
                split_from: None,
            };
            let (m, k) = (span.rows.len(), span.cols.len());
            let rank = r.number()?;
            let data = if rank == -1.0 {
                Data::Dense(r.f32s(m * k)?)
            } else {
                let rank = r.checked(rank, m.min(k))?;
                Data::LowRank {
                    rank,
                    u: r.f32s(rank * m)?,
                    v: r.f32s(rank * k)?,
                }
            };
            blocks.push(Block { span, data });
        }
        let compression = Compression {
            near_blocks: r.index(block_count)?,
            low_rank_blocks: r.index(block_count)?,
            guard_fallbacks: r.index(block_count)?,
            rank_fallbacks: r.index(block_count)?,
            shaded_blocks: r.index(block_count)?,
            shade_splits: r.index(block_count)?,
            shade_misfit: r.number()?,
            max_rank: r.index(n)?,
            mean_rank: r.number()?,
            low_rank_share: r.number()?,
            entries_read: r.number()?,
            row_error: r.number()?,
        };
        if r.at != values.len() {
            return Err("numbers left over after the operator".into());
        }
        let mut by_row = vec![Vec::new(); nodes.len()];
        let mut by_col = vec![Vec::new(); nodes.len()];
        for (b, block) in blocks.iter().enumerate() {
            by_row[block.span.row_node].push(b);
            if !block.span.is_diagonal() {
                by_col[block.span.col_node].push(b);
            }
        }
        Ok(Hierarchical {
            nodes,
            order,
            position,
            root_area,
            blocks,
            by_row,
            by_col,
            compression,
        })
    }
}

/// The numbers in order; running out or a malformed number is an error, never a panic.
struct Values<'a> {
    values: &'a [f64],
    at: usize,
}

impl<'a> Values<'a> {
    fn take(&mut self, len: usize) -> Result<&'a [f64], String> {
        let end = self.at.checked_add(len).ok_or("too few numbers")?;
        let slice = self.values.get(self.at..end).ok_or("too few numbers")?;
        self.at = end;
        Ok(slice)
    }

    fn number(&mut self) -> Result<f64, String> {
        Ok(self.take(1)?[0])
    }

    /// An index stored as a number, at most `max`.
    fn index(&mut self, max: usize) -> Result<usize, String> {
        let x = self.number()?;
        self.checked(x, max)
    }

    fn checked(&self, x: f64, max: usize) -> Result<usize, String> {
        if x >= 0.0 && x.fract() == 0.0 && x <= max as f64 {
            Ok(x as usize)
        } else {
            Err(format!("{x} where an index up to {max} belongs"))
        }
    }

    /// `len` single-precision numbers stored widened.
    fn f32s(&mut self, len: usize) -> Result<Vec<f32>, String> {
        self.take(len)?
            .iter()
            .map(|&x| {
                let y = x as f32;
                if f64::from(y).to_bits() == x.to_bits() {
                    Ok(y)
                } else {
                    Err(format!("{x} is no single-precision number"))
                }
            })
            .collect()
    }
}
