//! The kinetic energy of a cluster's balls, each with its own mass and moment of inertia
//! from the crate's [`Ball`] (1/2 m v^2 + 1/2 I w^2): the energy balances of the cluster
//! tests read it in and out. A sum of the balls' inputs and outputs, no expected value.

use billiard_contact::nalgebra::Vector3;
use billiard_contact::ClusterBall;

/// The kinetic energy (J) of `balls` moving at `states` (velocity, spin), in order.
pub fn kinetic<'a>(
    balls: &[ClusterBall],
    states: impl IntoIterator<Item = (&'a Vector3<f64>, &'a Vector3<f64>)>,
) -> f64 {
    balls
        .iter()
        .zip(states)
        .map(|(b, (v, w))| {
            0.5 * b.ball.mass() * v.norm_squared() + 0.5 * b.ball.inertia() * w.norm_squared()
        })
        .sum()
}
