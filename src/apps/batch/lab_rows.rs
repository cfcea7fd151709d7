//! Lab-frame collisions read where the caller keeps them and written into its columns: the
//! entry point for callers with their own memory layout (the Python bindings' numpy arrays).
//!
//! Row i: its lab scene, the [`Frame`] of the scene ([`Frame::of_pair`], the setup's balls), the setup's method on the
//! centre-of-mass state, then the outgoing lab motions and the throw angle
//! ([`Frame::outgoing`]): the path of the lab rows of [`crate::batch::run_csv`], without the
//! per-row overrides, the stick time and the text.

use crate::apps::batch::engine::{resolve_with, BatchInput, BatchSetup};
use crate::base::error::Error;
use crate::base::method::Method;
use crate::closed_form::kernel::ClosedFormBatch;
use crate::model::frame::{Frame, LabScene};
use crate::model::result::ContactResult;
use crate::model::state::{CmState, LabBall, LabMotion};
use nalgebra::Vector3;

/// Rows from which [`resolve_lab_into`] spreads the work over rayon's current pool; fewer
/// rows are resolved on the calling thread (handing them to the pool costs more than it
/// saves below this: `cargo bench --bench lab_rows` measures the cut-over).
pub const PARALLEL_LAB_ROWS: usize = 2048;

/// Rows per parallel work item.
const CHUNK_ROWS: usize = 1024;

/// Lab-frame input rows, read in place.
pub trait LabRows: Sync {
    /// The number of rows.
    fn len(&self) -> usize;

    /// True when there are no rows.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Row `i` (`i < len()`), or the error naming what is wrong with it (a reader that
    /// converts numbers checks them here; [`Frame::new`] checks that the balls touch and
    /// that `up` is a direction, the method that the state is finite).
    fn row(&self, i: usize) -> Result<LabScene, Error>;
}

impl LabRows for [LabScene] {
    fn len(&self) -> usize {
        <[LabScene]>::len(self)
    }

    #[inline]
    fn row(&self, i: usize) -> Result<LabScene, Error> {
        Ok(self[i])
    }
}

/// Where [`resolve_lab_into`] writes: element i of every column belongs to row i (vectors
/// as `[x, y, z]`, lab frame).
#[derive(Debug)]
pub struct LabOutColumns<'a> {
    /// Outgoing velocity of A (m/s).
    pub va: &'a mut [[f64; 3]],
    /// Outgoing spin of A (rad/s).
    pub wa: &'a mut [[f64; 3]],
    /// Outgoing velocity of B (m/s).
    pub vb: &'a mut [[f64; 3]],
    /// Outgoing spin of B (rad/s).
    pub wb: &'a mut [[f64; 3]],
    /// Normal impulse P (N s).
    pub impulse: &'a mut [f64],
    /// Tangential (friction) impulse J (N s).
    pub tangential_impulse: &'a mut [f64],
    /// Whether sliding stopped during the contact.
    pub sticks: &'a mut [bool],
    /// Throw angle (degrees, [`Frame::throw_angle_deg`]); NaN where it is undefined.
    pub throw_angle_deg: &'a mut [f64],
}

impl<'a> LabOutColumns<'a> {
    /// The number of rows of the columns, when they all have it.
    fn rows(&self) -> Option<usize> {
        let n = self.impulse.len();
        let lens = [
            self.va.len(),
            self.wa.len(),
            self.vb.len(),
            self.wb.len(),
            self.tangential_impulse.len(),
            self.sticks.len(),
            self.throw_angle_deg.len(),
        ];
        lens.iter().all(|&l| l == n).then_some(n)
    }

    /// Rows [0, k) and [k, n) of every column (`k` at most the shortest column's length).
    pub fn split_at(self, k: usize) -> (LabOutColumns<'a>, LabOutColumns<'a>) {
        let (va0, va1) = self.va.split_at_mut(k);
        let (wa0, wa1) = self.wa.split_at_mut(k);
        let (vb0, vb1) = self.vb.split_at_mut(k);
        let (wb0, wb1) = self.wb.split_at_mut(k);
        let (p0, p1) = self.impulse.split_at_mut(k);
        let (j0, j1) = self.tangential_impulse.split_at_mut(k);
        let (s0, s1) = self.sticks.split_at_mut(k);
        let (t0, t1) = self.throw_angle_deg.split_at_mut(k);
        let part =
            |va, wa, vb, wb, impulse, tangential_impulse, sticks, throw_angle_deg| LabOutColumns {
                va,
                wa,
                vb,
                wb,
                impulse,
                tangential_impulse,
                sticks,
                throw_angle_deg,
            };
        (
            part(va0, wa0, vb0, wb0, p0, j0, s0, t0),
            part(va1, wa1, vb1, wb1, p1, j1, s1, t1),
        )
    }
}

/// Resolves `rows` with the setup's method into `out` (element i of each column for row i),
/// in parallel over rayon's current pool from [`PARALLEL_LAB_ROWS`] rows on, else on this
/// thread. The setup's balls, contact and effects hold for every row.
///
/// On failure: the first failing row's index and error (the rows before it are written;
/// rows after it may be too). Columns whose lengths differ from the number of rows fail at
/// the first row that has no input or no place in a column.
///
/// ```
/// use billiard_contact::batch::{resolve_lab_into, BatchSetup, LabOutColumns};
/// use billiard_contact::{LabBall, LabScene, Method, Scene, SolverSettings};
/// use nalgebra::Vector3;
/// let scene = Scene::default_scene();
/// let r = scene.balls.a.radius();
/// let setup = BatchSetup::from_scene(&scene, SolverSettings::default().with_method(Method::ClosedForm));
/// // Head on along +y: A at 2 m/s onto B at rest (eq 52 with e = 1: they exchange velocities).
/// let head_on = LabScene {
///     a: LabBall { position: Vector3::zeros(), velocity: Vector3::new(0.0, 2.0, 0.0), spin: Vector3::zeros() },
///     b: LabBall { position: Vector3::new(0.0, 2.0 * r, 0.0), velocity: Vector3::zeros(), spin: Vector3::zeros() },
///     up: Vector3::z(),
/// };
/// let (mut va, mut wa, mut vb, mut wb) = ([[0.0; 3]], [[0.0; 3]], [[0.0; 3]], [[0.0; 3]]);
/// let (mut p, mut j, mut sticks, mut throw) = ([0.0], [0.0], [false], [0.0]);
/// let out = LabOutColumns {
///     va: &mut va, wa: &mut wa, vb: &mut vb, wb: &mut wb, impulse: &mut p,
///     tangential_impulse: &mut j, sticks: &mut sticks, throw_angle_deg: &mut throw,
/// };
/// resolve_lab_into(&setup, &[head_on][..], out).unwrap();
/// assert_eq!((va[0], vb[0]), ([0.0, 0.0, 0.0], [0.0, 2.0, 0.0]));
/// assert_eq!(p[0], 2.0 * scene.balls.a.mass()); // P = 2 m U(0), U(0) = 1 m/s
/// assert_eq!(throw[0], 0.0); // no slip, no throw: B leaves along the line of centres
/// ```
pub fn resolve_lab_into<R: LabRows + ?Sized>(
    setup: &BatchSetup,
    rows: &R,
    out: LabOutColumns<'_>,
) -> Result<(), (usize, Error)> {
    let n = rows.len();
    let columns = out.rows();
    if columns != Some(n) {
        let shortest = out.va.len().min(out.wa.len()).min(out.vb.len());
        let shortest = shortest.min(out.wb.len()).min(out.impulse.len());
        let shortest = shortest
            .min(out.tangential_impulse.len())
            .min(out.sticks.len());
        let first = shortest.min(out.throw_angle_deg.len()).min(n);
        return Err((
            first,
            Error::invalid(
                "out",
                format!("columns of {:?} rows for {n} input rows", columns),
                "one element per row in every column",
            ),
        ));
    }
    let kernel = (setup.settings.method() == Method::ClosedForm)
        .then(|| ClosedFormBatch::new(setup.balls, setup.contact, setup.effects));
    let job = Job {
        setup,
        kernel: kernel.as_ref(),
        rows,
    };
    if n >= PARALLEL_LAB_ROWS {
        job.parallel(0, out)
    } else {
        job.serial(0, out)
    }
}

/// What every part of a call shares.
struct Job<'s, R: ?Sized> {
    setup: &'s BatchSetup,
    /// The closed form of the setup's parameters, when that is the method.
    kernel: Option<&'s ClosedFormBatch>,
    rows: &'s R,
}

impl<R: LabRows + ?Sized> Job<'_, R> {
    /// Rows [start, start + out's length), halved over rayon's pool down to [`CHUNK_ROWS`];
    /// the first failing row of the range.
    fn parallel(&self, start: usize, out: LabOutColumns<'_>) -> Result<(), (usize, Error)> {
        let n = out.impulse.len();
        if n <= CHUNK_ROWS {
            return self.serial(start, out);
        }
        let half = n / 2;
        let (head, tail) = out.split_at(half);
        let (a, b) = rayon::join(
            || self.parallel(start, head),
            || self.parallel(start + half, tail),
        );
        a.and(b)
    }

    /// Rows [start, start + out's length) on this thread, in order. The closed form takes
    /// the rows [`BLOCK`] at a time in two passes (the frames, then the closed form and the
    /// outgoing motions): the square roots and divisions of one row wait on each other,
    /// those of neighbouring rows do not, and a short pass lets the processor overlap them
    /// (`benches/lab_rows.rs`: a fifth less time per row than one row after the other).
    fn serial(&self, start: usize, out: LabOutColumns<'_>) -> Result<(), (usize, Error)> {
        let n = out.impulse.len();
        let mut w = Writer {
            va: &mut out.va[..n],
            wa: &mut out.wa[..n],
            vb: &mut out.vb[..n],
            wb: &mut out.wb[..n],
            impulse: &mut out.impulse[..n],
            tangential_impulse: &mut out.tangential_impulse[..n],
            sticks: &mut out.sticks[..n],
            throw_angle_deg: &mut out.throw_angle_deg[..n],
        };
        // Fewer rows than a block (a single collision, say): row by row, without the
        // block's placeholders to set up.
        let Some(kernel) = self.kernel.filter(|_| n >= BLOCK) else {
            for k in 0..n {
                let i = start + k;
                let (r, motions) = self.row(i).map_err(|e| (i, e))?;
                w.put(k, &r, &motions);
            }
            return Ok(());
        };
        let balls = &self.setup.balls;
        let mut block = Block::new();
        for first in (0..n).step_by(BLOCK) {
            let m = BLOCK.min(n - first);
            // Pass 1: the frames, up to the first row that fails.
            let mut framed = 0;
            let mut failed = None;
            for q in 0..m {
                let lab = match self.rows.row(start + first + q) {
                    Ok(lab) => lab,
                    Err(e) => {
                        failed = Some(e);
                        break;
                    }
                };
                match Frame::of_pair(&lab, balls) {
                    Ok(frame) => {
                        block.frames[q] = frame;
                        block.labs[q] = lab;
                        framed += 1;
                    }
                    Err(e) => {
                        failed = Some(e);
                        break;
                    }
                }
            }
            // Pass 2: the closed form of the rows framed, up to the first that fails (it
            // comes before the one that failed in pass 1).
            let mut resolved = framed;
            for q in 0..framed {
                let cm = block.frames[q].to_cm(&block.labs[q]);
                match kernel.resolve_without_theta(&cm) {
                    Ok(r) => block.results[q] = r,
                    Err(e) => {
                        resolved = q;
                        failed = Some(e);
                        break;
                    }
                }
            }
            // Pass 3: the outgoing lab motions of the rows before the first failure.
            for q in 0..resolved {
                let r = &block.results[q];
                w.put(
                    first + q,
                    r,
                    &block.frames[q].outgoing(&block.labs[q], &r.out, r.collided()),
                );
            }
            if let Some(e) = failed {
                return Err((start + first + resolved, e));
            }
        }
        Ok(())
    }

    /// One row: its frame, the method on the centre-of-mass state, the outgoing motions.
    #[inline(always)]
    fn row(&self, i: usize) -> Result<(ContactResult, Motions), Error> {
        let lab = self.rows.row(i)?;
        let frame = Frame::of_pair(&lab, &self.setup.balls)?;
        let cm = frame.to_cm(&lab);
        let result = match self.kernel {
            Some(k) => k.resolve_without_theta(&cm)?,
            None => resolve_with(self.setup, None, &BatchInput::cm(cm))?.result,
        };
        Ok((result, frame.outgoing(&lab, &result.out, result.collided())))
    }
}

/// Outgoing lab motions of A and B and the throw angle of one row.
type Motions = (LabMotion, LabMotion, Option<f64>);

/// Rows per block of [`Job::serial`]'s passes.
const BLOCK: usize = 8;

/// A block of rows between the passes.
struct Block {
    labs: [LabScene; BLOCK],
    frames: [Frame; BLOCK],
    results: [ContactResult; BLOCK],
}

impl Block {
    /// Placeholders, overwritten by pass 1 before pass 2 reads them.
    fn new() -> Self {
        let zero = Vector3::zeros();
        let ball = LabBall {
            position: zero,
            velocity: zero,
            spin: zero,
        };
        Block {
            labs: [LabScene {
                a: ball,
                b: ball,
                up: Vector3::z(),
            }; BLOCK],
            frames: [Frame::paper(); BLOCK],
            results: [ContactResult {
                impulse: 0.0,
                s0: 0.0,
                theta: None,
                s_out: 0.0,
                sticks: false,
                stick_impulse: None,
                tangential_impulse: 0.0,
                heat: 0.0,
                heat_sliding: 0.0,
                out: CmState::new(zero, zero, zero),
            }; BLOCK],
        }
    }
}

/// The columns of [`Job::serial`], each of its rows.
struct Writer<'w> {
    va: &'w mut [[f64; 3]],
    wa: &'w mut [[f64; 3]],
    vb: &'w mut [[f64; 3]],
    wb: &'w mut [[f64; 3]],
    impulse: &'w mut [f64],
    tangential_impulse: &'w mut [f64],
    sticks: &'w mut [bool],
    throw_angle_deg: &'w mut [f64],
}

impl Writer<'_> {
    #[inline(always)]
    fn put(&mut self, k: usize, r: &ContactResult, (a, b, throw): &Motions) {
        self.va[k] = a.velocity.into();
        self.wa[k] = a.spin.into();
        self.vb[k] = b.velocity.into();
        self.wb[k] = b.spin.into();
        self.impulse[k] = r.impulse;
        self.tangential_impulse[k] = r.tangential_impulse;
        self.sticks[k] = r.sticks;
        self.throw_angle_deg[k] = throw.unwrap_or(f64::NAN);
    }
}
