//! The bounded-variable primal simplex that solves a level problem, as the module
//! documentation of [`target`](super) describes it: its tableau, both phases, the pivots.

use super::bound::{row_scale, Bound};
use super::limits::{FEASIBILITY, MAX_BOUNDS, MAX_CONTROLS, MAX_PIVOTS};
use crate::error::{Error, Result};

/// A tableau entry at most this in magnitude is not used as a pivot (rows are scaled to
/// entries of at most 1).
const PIVOT_TOL: f32 = 1.0e-5;
/// A reduced cost at most this in magnitude counts as zero (costs are scaled to at most 1).
const COST_TOL: f32 = 1.0e-6;
/// Columns: the levels, then `t`, `p` and `q` of every bound.
const COLUMNS: usize = MAX_CONTROLS + 3 * MAX_BOUNDS;

/// The state of the bounded-variable simplex. Variable `k`: level `k` for `k < m`; `t`, `p`,
/// `q` of bound `j` at `m + j`, `m + r + j`, `m + 2r + j`.
pub(super) struct Tableau {
    m: usize,
    r: usize,
    /// `B⁻¹ G'` (rows scaled): one row per bound, one column per level.
    a: [[f32; MAX_CONTROLS]; MAX_BOUNDS],
    /// `B⁻¹`.
    inv: [[f32; MAX_BOUNDS]; MAX_BOUNDS],
    /// Scaled right-hand sides `(lower − ambient)/s`.
    rhs: [f32; MAX_BOUNDS],
    /// Row scales `s`.
    scale: [f32; MAX_BOUNDS],
    /// Value of each row's basic variable.
    beta: [f32; MAX_BOUNDS],
    /// Basic variable of each row.
    head: [usize; MAX_BOUNDS],
    lo: [f32; COLUMNS],
    hi: [f32; COLUMNS],
    /// A non-basic variable is at `hi` (else at `lo`).
    at_upper: [bool; COLUMNS],
    basic: [bool; COLUMNS],
    cost: [f32; COLUMNS],
    pivots: u32,
}

impl Tableau {
    /// The starting basis for these weights and bounds: every level at 0, and each row's
    /// `t`, `p` or `q` basic.
    pub(super) fn new(weights: &[f32], bounds: &[Bound]) -> Self {
        let m = weights.len();
        let r = bounds.len();
        let mut t = Tableau {
            m,
            r,
            a: [[0.0; MAX_CONTROLS]; MAX_BOUNDS],
            inv: [[0.0; MAX_BOUNDS]; MAX_BOUNDS],
            rhs: [0.0; MAX_BOUNDS],
            scale: [1.0; MAX_BOUNDS],
            beta: [0.0; MAX_BOUNDS],
            head: [0; MAX_BOUNDS],
            lo: [0.0; COLUMNS],
            hi: [0.0; COLUMNS],
            at_upper: [false; COLUMNS],
            basic: [false; COLUMNS],
            cost: [0.0; COLUMNS],
            pivots: 0,
        };
        for k in 0..m {
            t.set_hi(k, 1.0);
        }
        for (j, b) in bounds.iter().enumerate() {
            let s = row_scale(b, m);
            let rhs = (b.lower - b.ambient) / s;
            let range = if b.upper == f32::INFINITY {
                f32::INFINITY
            } else {
                (b.upper - b.lower) / s
            };
            let (tj, pj, qj) = (m + j, m + r + j, m + 2 * r + j);
            t.set_hi(tj, range);
            // No upper bound: nothing can exceed it.
            t.set_hi(
                pj,
                if range == f32::INFINITY {
                    0.0
                } else {
                    f32::INFINITY
                },
            );
            t.set_hi(qj, f32::INFINITY);
            // Row j: Σ g'x − t − p + q = rhs, every level at 0 and t at 0 or its range.
            let (head, sign, value) = if rhs >= 0.0 {
                (qj, 1.0, rhs)
            } else if -rhs <= range {
                (tj, -1.0, -rhs)
            } else {
                if let Some(u) = t.at_upper.get_mut(tj) {
                    *u = true;
                }
                (pj, -1.0, -rhs - range)
            };
            if let (Some(arow), Some(irow)) = (t.a.get_mut(j), t.inv.get_mut(j)) {
                for (slot, &g) in arow.iter_mut().zip(&b.gains).take(m) {
                    *slot = sign * g / s;
                }
                if let Some(d) = irow.get_mut(j) {
                    *d = sign;
                }
            }
            set(&mut t.rhs, j, rhs);
            set(&mut t.scale, j, s);
            set(&mut t.beta, j, value);
            if let Some(h) = t.head.get_mut(j) {
                *h = head;
            }
            if let Some(bflag) = t.basic.get_mut(head) {
                *bflag = true;
            }
        }
        t
    }

    fn set_hi(&mut self, k: usize, v: f32) {
        set(&mut self.hi, k, v);
    }

    fn n(&self) -> usize {
        self.m + 3 * self.r
    }

    /// Entry of variable `k`'s column in row `i` of the current tableau.
    fn entry(&self, i: usize, k: usize) -> f32 {
        let (m, r) = (self.m, self.r);
        if k < m {
            return get2(&self.a, i, k);
        }
        let f = (k - m) / r.max(1);
        let j = (k - m) % r.max(1);
        let v = get2(&self.inv, i, j);
        // t and p enter their row with −1, q with +1.
        if f == 2 {
            v
        } else {
            -v
        }
    }

    /// Value of a non-basic variable.
    fn bound_value(&self, k: usize) -> f32 {
        if get(&self.at_upper, k) {
            get(&self.hi, k)
        } else {
            get(&self.lo, k)
        }
    }

    /// Every variable's value.
    fn values(&self) -> [f32; COLUMNS] {
        let mut v = [0.0f32; COLUMNS];
        for (k, slot) in v.iter_mut().enumerate().take(self.n()) {
            *slot = self.bound_value(k);
        }
        for i in 0..self.r {
            set(&mut v, get(&self.head, i), get(&self.beta, i));
        }
        v
    }

    /// Refines the basic values against the original rows, twice: `β += B⁻¹ (rhs − A x)`.
    /// Rounding then does not accumulate in them from one pivot to the next.
    fn refresh(&mut self, bounds: &[Bound]) {
        let (m, r) = (self.m, self.r);
        for _ in 0..2 {
            let x = self.values();
            let mut residual = [0.0f32; MAX_BOUNDS];
            for (j, b) in bounds.iter().enumerate().take(r) {
                let s = get(&self.scale, j);
                let mut v = get(&self.rhs, j);
                for c in 0..m {
                    v -= b.gains.get(c).copied().unwrap_or(0.0) / s * get(&x, c);
                }
                v += get(&x, m + j) + get(&x, m + r + j) - get(&x, m + 2 * r + j);
                set(&mut residual, j, v);
            }
            for i in 0..r {
                let mut v = get(&self.beta, i);
                for j in 0..r {
                    v += get2(&self.inv, i, j) * get(&residual, j);
                }
                set(&mut self.beta, i, v);
            }
        }
    }

    /// Both phases; the number of pivots and flips.
    pub(super) fn run(&mut self, weights: &[f32], bounds: &[Bound]) -> Result<u32> {
        let (m, r) = (self.m, self.r);
        // Phase 1: least total violation in lux, each row's p and q counted at its scale.
        let smax = self.scale.iter().take(r).fold(0.0f32, |a, &s| a.max(s));
        for j in 0..r {
            let c = get(&self.scale, j) / smax.max(f32::MIN_POSITIVE);
            set(&mut self.cost, m + r + j, c);
            set(&mut self.cost, m + 2 * r + j, c);
        }
        self.optimise()?;
        self.refresh(bounds);
        let x = self.values();
        let feasible = (0..r).all(|j| get(&x, m + r + j) + get(&x, m + 2 * r + j) <= FEASIBILITY);
        if feasible {
            for k in m + r..m + 3 * r {
                set(&mut self.hi, k, 0.0);
                set(&mut self.at_upper, k, false);
            }
        } else {
            // Fix what cannot move without raising the violation.
            let d = self.reduced_costs();
            for k in 0..self.n() {
                if !get(&self.basic, k) && get(&d, k).abs() > COST_TOL {
                    let v = self.bound_value(k);
                    set(&mut self.lo, k, v);
                    set(&mut self.hi, k, v);
                }
            }
        }
        // Phase 2: least power.
        self.cost = [0.0; COLUMNS];
        let wmax = weights.iter().fold(0.0f32, |a, &w| a.max(w));
        if wmax > 0.0 {
            for (c, &w) in weights.iter().enumerate() {
                set(&mut self.cost, c, w / wmax);
            }
        }
        self.optimise()?;
        self.refresh(bounds);
        Ok(self.pivots)
    }

    /// `d_k = c_k − c_Bᵀ B⁻¹ A_k` for every variable.
    fn reduced_costs(&self) -> [f32; COLUMNS] {
        let (m, r) = (self.m, self.r);
        let mut pi = [0.0f32; MAX_BOUNDS];
        for j in 0..r {
            let mut v = 0.0;
            for i in 0..r {
                v += get(&self.cost, get(&self.head, i)) * get2(&self.inv, i, j);
            }
            set(&mut pi, j, v);
        }
        let mut d = [0.0f32; COLUMNS];
        for c in 0..m {
            let mut v = get(&self.cost, c);
            for i in 0..r {
                v -= get(&self.cost, get(&self.head, i)) * get2(&self.a, i, c);
            }
            set(&mut d, c, v);
        }
        for j in 0..r {
            let p = get(&pi, j);
            set(&mut d, m + j, get(&self.cost, m + j) + p);
            set(&mut d, m + r + j, get(&self.cost, m + r + j) + p);
            set(&mut d, m + 2 * r + j, get(&self.cost, m + 2 * r + j) - p);
        }
        d
    }

    /// Bland's-rule simplex on the current costs, until no variable improves.
    fn optimise(&mut self) -> Result<()> {
        while self.step()? {}
        Ok(())
    }

    /// One pivot or bound flip; `false` when no variable improves the objective.
    fn step(&mut self) -> Result<bool> {
        let (r, n) = (self.r, self.n());
        {
            let d = self.reduced_costs();
            let entering = (0..n).find(|&k| {
                let dk = get(&d, k);
                !get(&self.basic, k)
                    && get(&self.hi, k) > get(&self.lo, k)
                    && if get(&self.at_upper, k) {
                        dk > COST_TOL
                    } else {
                        dk < -COST_TOL
                    }
            });
            let Some(k) = entering else {
                return Ok(false);
            };
            if self.pivots >= MAX_PIVOTS {
                return Err(Error::PivotLimit {
                    pivots: self.pivots,
                });
            }
            self.pivots += 1;
            let dir = if get(&self.at_upper, k) { -1.0 } else { 1.0 };
            let mut col = [0.0f32; MAX_BOUNDS];
            for i in 0..r {
                set(&mut col, i, self.entry(i, k));
            }
            // Ratio test: the entering variable's own range, then each basic variable.
            let mut theta = get(&self.hi, k) - get(&self.lo, k);
            let mut leave: Option<(usize, bool)> = None;
            for i in 0..r {
                let alpha = get(&col, i) * dir;
                let b = get(&self.head, i);
                let beta = get(&self.beta, i);
                let (limit, to_upper) = if alpha > PIVOT_TOL {
                    ((beta - get(&self.lo, b)) / alpha, false)
                } else if alpha < -PIVOT_TOL && get(&self.hi, b) < f32::INFINITY {
                    ((get(&self.hi, b) - beta) / -alpha, true)
                } else {
                    continue;
                };
                let limit = limit.max(0.0);
                let better = match leave {
                    _ if limit < theta => true,
                    Some((l, _)) => limit == theta && b < get(&self.head, l),
                    None => false,
                };
                if better {
                    theta = limit;
                    leave = Some((i, to_upper));
                }
            }
            if theta == f32::INFINITY {
                // An improving ray: impossible with levels in [0, 1] and costs ≥ 0.
                return Err(Error::PivotLimit {
                    pivots: self.pivots,
                });
            }
            for i in 0..r {
                let v = get(&self.beta, i) - get(&col, i) * dir * theta;
                set(&mut self.beta, i, v);
            }
            let Some((row, to_upper)) = leave else {
                let flipped = !get(&self.at_upper, k);
                set(&mut self.at_upper, k, flipped);
                return Ok(true);
            };
            let entering_value = self.bound_value(k) + dir * theta;
            let out = get(&self.head, row);
            set(&mut self.basic, out, false);
            set(&mut self.at_upper, out, to_upper);
            set(&mut self.basic, k, true);
            set(&mut self.at_upper, k, false);
            if let Some(h) = self.head.get_mut(row) {
                *h = k;
            }
            set(&mut self.beta, row, entering_value);
            self.pivot(row, &col);
        }
        Ok(true)
    }

    /// Gauss–Jordan step on `row`, whose entry in the entering column `col` is the pivot.
    fn pivot(&mut self, row: usize, col: &[f32; MAX_BOUNDS]) {
        let (m, r) = (self.m, self.r);
        let p = get(col, row);
        if p == 0.0 {
            return;
        }
        let (mut prow_a, mut prow_inv) = (
            self.a.get(row).copied().unwrap_or([0.0; MAX_CONTROLS]),
            self.inv.get(row).copied().unwrap_or([0.0; MAX_BOUNDS]),
        );
        for v in prow_a.iter_mut().take(m) {
            *v /= p;
        }
        for v in prow_inv.iter_mut().take(r) {
            *v /= p;
        }
        for i in 0..r {
            let (Some(arow), Some(irow)) = (self.a.get_mut(i), self.inv.get_mut(i)) else {
                continue;
            };
            if i == row {
                *arow = prow_a;
                *irow = prow_inv;
                continue;
            }
            let f = get(col, i);
            if f == 0.0 {
                continue;
            }
            for (v, &pv) in arow.iter_mut().zip(&prow_a).take(m) {
                *v -= f * pv;
            }
            for (v, &pv) in irow.iter_mut().zip(&prow_inv).take(r) {
                *v -= f * pv;
            }
        }
    }

    /// The levels, clamped to [0, 1] against rounding.
    pub(super) fn levels(&self, out: &mut [f32]) {
        let x = self.values();
        for (c, slot) in out.iter_mut().enumerate().take(self.m) {
            *slot = get(&x, c).clamp(0.0, 1.0);
        }
    }
}

fn get<T: Copy + Default>(v: &[T], i: usize) -> T {
    v.get(i).copied().unwrap_or_default()
}

fn get2<const C: usize>(v: &[[f32; C]], i: usize, j: usize) -> f32 {
    v.get(i).and_then(|row| row.get(j)).copied().unwrap_or(0.0)
}

fn set<T>(v: &mut [T], i: usize, x: T) {
    if let Some(slot) = v.get_mut(i) {
        *slot = x;
    }
}
