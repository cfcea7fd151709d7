//! The right-hand side of the impact in scaled variables (m = r = 1, speeds over v_ref):
//! the derivatives of the state with respect to the cushion's normal impulse P_I, for each
//! state of the two contacts (docs/cushion.md#equations).
//!
//! Frame: x along the cushion, y towards it, z up; the ball's centre at the origin. The
//! cushion touches at r_I = (0, c, s), c = cos theta, s = sin theta, and pushes along
//! -r_I; its tangent plane has the directions t1 = (1, 0, 0), t2 = (0, -s, c). The cloth
//! touches at r_C = (0, 0, -1) and pushes along +z.

/// Length of the state: v (3), w (3), P_C, W.
pub(crate) const DIM: usize = 8;

/// The scaled state: [v_x, v_y, v_z, w_x, w_y, w_z, P_C, W].
pub(crate) type State = [f64; DIM];

/// Index of the table's normal impulse in the state.
pub(crate) const PC: usize = 6;
/// Index of the work of the normal force in the state.
pub(crate) const WORK: usize = 7;

/// Newton iterations of the quasi-static direction.
const QS_ITERATIONS: usize = 8;

/// A slip below this (scaled) has no direction: the contact uses its seed direction.
pub(crate) const DIRECTION_FLOOR: f64 = 1e-14;

/// The state of one contact's friction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Friction {
    /// Sliding: friction mu N against the slip measured from `origin` (the slip left at
    /// the last zero of the slip, a rounding error of the event's location, or 0). While
    /// that relative slip is at most `floor` (just after a reversal or a restart) the
    /// direction is the quasi-static one, along which the slip grows under its own
    /// friction (docs/cushion.md#slip-growing-from-zero), found from `seed`; below
    /// DIRECTION_FLOOR with floor 0, `seed` itself.
    Sliding {
        seed: [f64; 2],
        origin: [f64; 2],
        floor: f64,
    },
    /// Stuck: the friction that keeps the slip zero.
    Stuck,
    /// Sliding with friction against the given direction whatever the slip (for the
    /// quasi-static direction's solve).
    Fixed([f64; 2]),
}

/// The state of both contacts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Modes {
    /// Friction at the cushion.
    pub(crate) cushion: Friction,
    /// Friction at the cloth (ignored while airborne).
    pub(crate) table: Friction,
    /// The ball is off the cloth: no normal force and no friction there.
    pub(crate) airborne: bool,
}

/// The constants of the right-hand side.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rhs {
    /// cos theta.
    pub(crate) c: f64,
    /// sin theta.
    pub(crate) s: f64,
    /// 1 / alpha, with I = alpha m r^2 (a reciprocal: the evaluation multiplies by it).
    pub(crate) inv_alpha: f64,
    /// Friction at the cushion.
    pub(crate) mu_i: f64,
    /// Friction at the cloth.
    pub(crate) mu_c: f64,
}

/// The forces (per unit P_I) and derivatives at one state.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Eval {
    /// dy/dP_I.
    pub(crate) dy: State,
    /// Cushion friction in (t1, t2).
    pub(crate) f_i: [f64; 2],
    /// Cloth friction in (x, y).
    pub(crate) f_c: [f64; 2],
    /// Cloth normal force per unit P_I (dP_C/dP_I); negative when the constraint v_z = 0
    /// would need a pull (only meaningful on the cloth).
    pub(crate) n_c: f64,
}

/// The slip at the cushion in (t1, t2).
pub(crate) fn slip_cushion(rhs: &Rhs, y: &State) -> [f64; 2] {
    [
        y[0] + rhs.s * y[4] - rhs.c * y[5],
        -rhs.s * y[1] + rhs.c * y[2] + y[3],
    ]
}

/// The slip at the cloth in (x, y).
pub(crate) fn slip_table(y: &State) -> [f64; 2] {
    [y[0] - y[4], y[1] + y[3]]
}

/// The normal velocity at the cushion.
pub(crate) fn normal_velocity(rhs: &Rhs, y: &State) -> f64 {
    rhs.c * y[1] + rhs.s * y[2]
}

/// The unit vector along `s`, or `seed` when `s` has no direction.
fn direction(s: [f64; 2], seed: [f64; 2], origin: [f64; 2]) -> [f64; 2] {
    unit([s[0] - origin[0], s[1] - origin[1]], seed)
}

/// The unit vector along `s`, or `seed` when |s| <= DIRECTION_FLOOR. As s sqrt(q) / q
/// (q = |s|^2): the square root and the reciprocal run side by side, where s / sqrt(q)
/// waits for the root before it divides (the evaluation is a chain of dependent
/// operations, and these two were a third of its latency).
#[inline]
fn unit(s: [f64; 2], seed: [f64; 2]) -> [f64; 2] {
    let q = s[0] * s[0] + s[1] * s[1];
    if q > DIRECTION_FLOOR * DIRECTION_FLOOR {
        let k = q.sqrt() * (1.0 / q);
        [s[0] * k, s[1] * k]
    } else {
        seed
    }
}

impl Rhs {
    /// The derivatives of v and w for cushion friction `f_i`, cloth
    /// normal force `n_c` and cloth friction `f_c`.
    fn motion(&self, f_i: [f64; 2], n_c: f64, f_c: [f64; 2]) -> ([f64; 3], [f64; 3]) {
        let (c, s) = (self.c, self.s);
        // Cushion force -r_I + F1 t1 + F2 t2, cloth force (G1, G2, N_C).
        let dv = [
            f_i[0] + f_c[0],
            -c - f_i[1] * s + f_c[1],
            -s + f_i[1] * c + n_c,
        ];
        // r_I x f_I = (F2, s F1, -c F1); r_C x f_C = (G2, -G1, 0).
        let a = self.inv_alpha;
        let dw = [
            (f_i[1] + f_c[1]) * a,
            (s * f_i[0] - f_c[0]) * a,
            -c * f_i[0] * a,
        ];
        (dv, dw)
    }

    /// The slip rates at the cushion and at the cloth for the derivatives `dv`, `dw`.
    fn slip_rates(&self, dv: &[f64; 3], dw: &[f64; 3]) -> ([f64; 2], [f64; 2]) {
        (
            [
                dv[0] + self.s * dw[1] - self.c * dw[2],
                -self.s * dv[1] + self.c * dv[2] + dw[0],
            ],
            [dv[0] - dw[1], dv[1] + dw[0]],
        )
    }

    /// The forces for cushion friction `f_i` (given), the cloth's constraint and the cloth's
    /// friction: sliding along `dir_c`, or `stuck_c` when stuck.
    fn cloth(
        &self,
        modes: &Modes,
        f_i: [f64; 2],
        dir_c: [f64; 2],
        stuck_c: [f64; 2],
    ) -> (f64, [f64; 2]) {
        if modes.airborne {
            return (0.0, [0.0, 0.0]);
        }
        // v_z stays 0: -s + F2 c + N_C = 0.
        let n_c = self.s - f_i[1] * self.c;
        let f_c = match modes.table {
            Friction::Sliding { .. } | Friction::Fixed(_) => {
                let k = -self.mu_c * n_c;
                [k * dir_c[0], k * dir_c[1]]
            }
            Friction::Stuck => stuck_c,
        };
        (n_c, f_c)
    }

    /// The slip rates of the stuck contacts for the unknown frictions `x` (cushion's first
    /// when stuck, then the cloth's).
    fn stuck_rates(
        &self,
        modes: &Modes,
        dir_i: [f64; 2],
        dir_c: [f64; 2],
        x: &[f64; 4],
    ) -> [f64; 4] {
        let stuck_i = modes.cushion == Friction::Stuck;
        let f_i = if stuck_i {
            [x[0], x[1]]
        } else {
            [-self.mu_i * dir_i[0], -self.mu_i * dir_i[1]]
        };
        let k = if stuck_i { 2 } else { 0 };
        let (n_c, f_c) = self.cloth(modes, f_i, dir_c, [x[k], x[k + 1]]);
        let (dv, dw) = self.motion(f_i, n_c, f_c);
        let (ri, rc) = self.slip_rates(&dv, &dw);
        let mut out = [0.0; 4];
        let mut j = 0;
        if stuck_i {
            out[0] = ri[0];
            out[1] = ri[1];
            j = 2;
        }
        if modes.table == Friction::Stuck && !modes.airborne {
            out[j] = rc[0];
            out[j + 1] = rc[1];
        }
        out
    }

    /// The frictions of the stuck contacts: the affine slip rates solved for zero.
    fn stuck_forces(&self, modes: &Modes, dir_i: [f64; 2], dir_c: [f64; 2]) -> [f64; 4] {
        let n = 2 * usize::from(modes.cushion == Friction::Stuck)
            + 2 * usize::from(modes.table == Friction::Stuck && !modes.airborne);
        let mut x = [0.0; 4];
        if n == 0 {
            return x;
        }
        let r0 = self.stuck_rates(modes, dir_i, dir_c, &x);
        // Columns of the Jacobian (exact: the rates are affine in the frictions).
        let mut m = [[0.0; 5]; 4];
        for j in 0..n {
            let mut e = [0.0; 4];
            e[j] = 1.0;
            let rj = self.stuck_rates(modes, dir_i, dir_c, &e);
            for i in 0..n {
                m[i][j] = rj[i] - r0[i];
            }
        }
        for i in 0..n {
            m[i][4] = -r0[i];
        }
        solve_small(&mut m, n, &mut x);
        x
    }

    /// The friction direction of contact `k` (0 cushion, 1 cloth) at `y`.
    fn friction_direction(&self, modes: &Modes, y: &State, k: usize) -> [f64; 2] {
        let f = if k == 0 { modes.cushion } else { modes.table };
        match f {
            Friction::Sliding {
                seed,
                origin,
                floor,
            } => {
                let s = if k == 0 {
                    slip_cushion(self, y)
                } else {
                    slip_table(y)
                };
                let rel = [s[0] - origin[0], s[1] - origin[1]];
                if floor > 0.0 && rel[0] * rel[0] + rel[1] * rel[1] <= floor * floor {
                    self.quasi_static_direction(modes, y, k, seed)
                } else {
                    direction(s, seed, origin)
                }
            }
            Friction::Fixed(d) => d,
            Friction::Stuck => [0.0, 0.0],
        }
    }

    /// The direction d along which contact `k`'s slip, under friction -mu N d, grows: its
    /// slip rate c + M d (affine in d) parallel to d with a positive projection. Newton's
    /// method on the angle from `seed`.
    pub(crate) fn quasi_static_direction(
        &self,
        modes: &Modes,
        y: &State,
        k: usize,
        seed: [f64; 2],
    ) -> [f64; 2] {
        let rate = |d: [f64; 2]| {
            let mut m = *modes;
            if k == 0 {
                m.cushion = Friction::Fixed(d);
            } else {
                m.table = Friction::Fixed(d);
            }
            let e = self.eval(&m, y);
            let dv = [e.dy[0], e.dy[1], e.dy[2]];
            let dw = [e.dy[3], e.dy[4], e.dy[5]];
            let (ri, rc) = self.slip_rates(&dv, &dw);
            if k == 0 {
                ri
            } else {
                rc
            }
        };
        let c = rate([0.0, 0.0]);
        let r1 = rate([1.0, 0.0]);
        let r2 = rate([0.0, 1.0]);
        let m = [[r1[0] - c[0], r2[0] - c[0]], [r1[1] - c[1], r2[1] - c[1]]];
        // f(phi) = (c + M d) x d, d = (cos, sin).
        let f = |phi: f64| {
            let (sn, cs) = phi.sin_cos();
            let g = [
                c[0] + m[0][0] * cs + m[0][1] * sn,
                c[1] + m[1][0] * cs + m[1][1] * sn,
            ];
            let dg = [-m[0][0] * sn + m[0][1] * cs, -m[1][0] * sn + m[1][1] * cs];
            let val = g[0] * sn - g[1] * cs;
            let der = dg[0] * sn + g[0] * cs - dg[1] * cs + g[1] * sn;
            (val, der)
        };
        let mut phi = seed[1].atan2(seed[0]);
        for _ in 0..QS_ITERATIONS {
            let (val, der) = f(phi);
            if der == 0.0 {
                break;
            }
            let step = (val / der).clamp(-0.5, 0.5);
            phi -= step;
            if step.abs() < 1e-15 {
                break;
            }
        }
        let (sn, cs) = phi.sin_cos();
        let g = [
            c[0] + m[0][0] * cs + m[0][1] * sn,
            c[1] + m[1][0] * cs + m[1][1] * sn,
        ];
        if g[0] * cs + g[1] * sn >= 0.0 {
            [cs, sn]
        } else {
            [-cs, -sn]
        }
    }

    /// The forces and derivatives at `y` for `modes`.
    #[inline]
    pub(crate) fn eval(&self, modes: &Modes, y: &State) -> Eval {
        if let Some(e) = self.eval_sliding(modes, y) {
            return e;
        }
        self.eval_general(modes, y)
    }

    /// The common state, both contacts sliding on the cloth with their slips past any
    /// seed's floor, without the general path's matches and stuck-friction solve (the same
    /// arithmetic); None otherwise.
    #[inline]
    fn eval_sliding(&self, modes: &Modes, y: &State) -> Option<Eval> {
        let (
            Friction::Sliding {
                seed: seed_i,
                origin: o_i,
                floor: floor_i,
            },
            Friction::Sliding {
                seed: seed_c,
                origin: o_c,
                floor: floor_c,
            },
            false,
        ) = (modes.cushion, modes.table, modes.airborne)
        else {
            return None;
        };
        let si = slip_cushion(self, y);
        let sc = slip_table(y);
        let ri = [si[0] - o_i[0], si[1] - o_i[1]];
        let rc = [sc[0] - o_c[0], sc[1] - o_c[1]];
        let qi = ri[0] * ri[0] + ri[1] * ri[1];
        let qc = rc[0] * rc[0] + rc[1] * rc[1];
        if (floor_i > 0.0 && qi <= floor_i * floor_i) || (floor_c > 0.0 && qc <= floor_c * floor_c)
        {
            return None;
        }
        let dir_i = unit(ri, seed_i);
        let dir_c = unit(rc, seed_c);
        let f_i = [-self.mu_i * dir_i[0], -self.mu_i * dir_i[1]];
        let n_c = self.s - f_i[1] * self.c;
        let k = -self.mu_c * n_c;
        let f_c = [k * dir_c[0], k * dir_c[1]];
        let (mut dv, dw) = self.motion(f_i, n_c, f_c);
        dv[2] = 0.0;
        Some(Eval {
            dy: [
                dv[0],
                dv[1],
                dv[2],
                dw[0],
                dw[1],
                dw[2],
                n_c,
                normal_velocity(self, y),
            ],
            f_i,
            f_c,
            n_c,
        })
    }

    /// [`Rhs::eval`] for any state of the contacts.
    fn eval_general(&self, modes: &Modes, y: &State) -> Eval {
        let dir_i = self.friction_direction(modes, y, 0);
        let dir_c = if modes.airborne {
            [0.0, 0.0]
        } else {
            self.friction_direction(modes, y, 1)
        };
        let x = self.stuck_forces(modes, dir_i, dir_c);
        let f_i = match modes.cushion {
            Friction::Sliding { .. } | Friction::Fixed(_) => {
                [-self.mu_i * dir_i[0], -self.mu_i * dir_i[1]]
            }
            Friction::Stuck => [x[0], x[1]],
        };
        let k = if modes.cushion == Friction::Stuck {
            2
        } else {
            0
        };
        let (n_c, f_c) = self.cloth(modes, f_i, dir_c, [x[k], x[k + 1]]);
        let (mut dv, dw) = self.motion(f_i, n_c, f_c);
        if !modes.airborne {
            dv[2] = 0.0;
        }
        // Off the cloth the constraint's n_c tells whether the ball would be pressed back.
        let n_c_report = if modes.airborne {
            self.s - f_i[1] * self.c
        } else {
            n_c
        };
        Eval {
            dy: [
                dv[0],
                dv[1],
                dv[2],
                dw[0],
                dw[1],
                dw[2],
                n_c,
                normal_velocity(self, y),
            ],
            f_i,
            f_c,
            n_c: n_c_report,
        }
    }
}

/// Gaussian elimination with partial pivoting of the n x n system in `m` (right-hand side
/// in column 4) into `x`. A singular system leaves its unknowns 0.
fn solve_small(m: &mut [[f64; 5]; 4], n: usize, x: &mut [f64; 4]) {
    for col in 0..n {
        let mut piv = col;
        for row in col + 1..n {
            if m[row][col].abs() > m[piv][col].abs() {
                piv = row;
            }
        }
        m.swap(col, piv);
        let d = m[col][col];
        if d == 0.0 {
            continue;
        }
        let pivot = m[col];
        for r in m.iter_mut().take(n).skip(col + 1) {
            let f = r[col] / d;
            for (a, b) in r.iter_mut().zip(&pivot).skip(col) {
                *a -= f * b;
            }
        }
    }
    for col in (0..n).rev() {
        let mut acc = m[col][4];
        for k in col + 1..n {
            acc -= m[col][k] * x[k];
        }
        x[col] = if m[col][col] == 0.0 {
            0.0
        } else {
            acc / m[col][col]
        };
    }
}
