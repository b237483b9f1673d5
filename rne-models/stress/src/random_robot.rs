//! Random serial robots: mixed revolute and prismatic joints, random standard-DH geometry and
//! physically valid random inertias, from a seeded generator.

use rand::Rng;
use rand_chacha::ChaCha8Rng;

use super::chain::{Chain, ChainLink, JointType};

/// The probability that a joint is prismatic.
const PRISMATIC: f64 = 0.3;

/// A random robot with `joints` links (standard DH, 30 % prismatic joints): a, d in
/// [−0.5, 0.5] m, α, θ in [−π, π], mass in [0.1, 20] kg, centre of mass within 0.3 m of the
/// frame origin, and gravity of up to 10 m/s² in a random direction.
///
/// The inertia about the centre of mass is R diag(I₁, I₂, I₃) Rᵀ with a random rotation R
/// (roll–pitch–yaw) and principal moments (x + y, y + z, z + x) · m / 100 for positive
/// x, y, z: positive definite and within the triangle inequality by construction.
pub fn random_robot(rng: &mut ChaCha8Rng, joints: usize) -> Chain {
    let pi = std::f64::consts::PI;
    let links = (0..joints)
        .map(|_| {
            let joint = if rng.gen_bool(PRISMATIC) {
                JointType::Prismatic
            } else {
                JointType::Revolute
            };
            let (a, alpha, d, theta) = (
                rng.gen_range(-0.5..=0.5),
                rng.gen_range(-pi..=pi),
                rng.gen_range(-0.5..=0.5),
                rng.gen_range(-pi..=pi),
            );
            let mass = rng.gen_range(0.1..=20.0);
            let com = [0; 3].map(|_| rng.gen_range(-0.3..=0.3));
            let raw = [0; 3].map(|_| rng.gen_range(0.01..=1.0));
            let moments =
                [raw[0] + raw[1], raw[1] + raw[2], raw[2] + raw[0]].map(|m| m * mass / 100.0);
            let axes = rotation([0; 3].map(|_| rng.gen_range(-pi..=pi)));
            let inertia =
                |i: usize, j: usize| (0..3).map(|k| axes[i][k] * moments[k] * axes[j][k]).sum();
            ChainLink {
                joint,
                a,
                alpha,
                d,
                theta,
                mass,
                com,
                inertia: [
                    inertia(0, 0),
                    inertia(1, 1),
                    inertia(2, 2),
                    inertia(0, 1),
                    inertia(0, 2),
                    inertia(1, 2),
                ],
            }
        })
        .collect();
    let direction = rotation([0; 3].map(|_| rng.gen_range(-pi..=pi)));
    let g = rng.gen_range(0.0..=10.0);
    Chain {
        name: format!("random-{joints}"),
        gravity: [
            direction[0][2] * g,
            direction[1][2] * g,
            direction[2][2] * g,
        ],
        links,
    }
}

/// The rotation Rz(yaw) Ry(pitch) Rx(roll) of roll–pitch–yaw angles.
fn rotation([roll, pitch, yaw]: [f64; 3]) -> [[f64; 3]; 3] {
    let (sr, cr) = roll.sin_cos();
    let (sp, cp) = pitch.sin_cos();
    let (sy, cy) = yaw.sin_cos();
    [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    /// Random robots of every size are valid specs, and the generator is reproducible.
    #[test]
    fn random_robots_are_valid_and_seeded() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for n in 1..=12 {
            let robot = random_robot(&mut rng, n);
            assert_eq!(robot.model().unwrap().dof(), n);
        }
        let again = |seed| random_robot(&mut ChaCha8Rng::seed_from_u64(seed), 5);
        assert_eq!(again(3), again(3));
    }
}
