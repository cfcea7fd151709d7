//! The warnings of a scene: values far outside any ball game's (a unit slip, most likely)
//! and settings no method uses with it.

use crate::base::plausible::{Plausible, DURATION, MASS, RADIUS, YOUNGS_MODULUS};
use crate::profile::force::ForceProfile;
use crate::scene::types::Scene;

impl Scene {
    /// The warnings of a scene's values (balls, material, contact duration), one line each;
    /// unequal balls (`[balls.a]`, `[balls.b]`) are named by their own fields. Also a
    /// `[solver] time_transform` under a contact law, which no method uses.
    pub fn warnings(&self) -> Vec<String> {
        let scene = self;
        let (a, b) = (&scene.balls.a, &scene.balls.b);
        let mut checks = if a == b {
            vec![(MASS, a.mass()), (RADIUS, a.radius())]
        } else {
            let named = |p: Plausible, field| Plausible { field, ..p };
            vec![
                (named(MASS, "balls.a.mass"), a.mass()),
                (named(RADIUS, "balls.a.radius"), a.radius()),
                (named(MASS, "balls.b.mass"), b.mass()),
                (named(RADIUS, "balls.b.radius"), b.radius()),
            ]
        };
        match &scene.material {
            // The duration follows from the material (and the checked mass and radius).
            Some(m) => checks.push((YOUNGS_MODULUS, m.youngs_modulus())),
            None => checks.push((DURATION, scene.profile.duration())),
        }
        let mut warnings: Vec<String> = checks
            .into_iter()
            .filter_map(|(p, v)| p.warning(v))
            .collect();
        // A key of the scene's own [solver] that no method uses with this scene: the time
        // transform under a contact law (the tolerances depend on the method, which a command
        // line may still change, so they are judged with the run's options instead).
        if scene.law.is_some() {
            for (field, why) in scene.solver_given.unused(&scene.solver, true) {
                if field == "time_transform" {
                    warnings.push(format!("[solver] {field} has no effect with {why}"));
                }
            }
        }
        warnings
    }
}
