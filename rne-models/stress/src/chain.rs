//! Serial robots in standard Denavit–Hartenberg form, built in code and written as TOML specs
//! (docs/design.md §2.1): the stress robots whose masses, lengths and inertias are pushed to
//! extremes.
//!
//! Going through the spec text, rather than building a model directly, means each stress robot
//! passes the same reader and checks (positive mass, positive-definite inertia, triangle
//! inequality) as a user's file, and can be written out to reproduce a case with `rne`.

use std::f64::consts::FRAC_PI_2;

use rne_symbolic::spec::{LoadOptions, SpecError};
use rne_symbolic::RobotModel;
use rne_symbolic::{read_robot, Description};

/// How a link moves relative to its parent.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointType {
    /// Rotation about the DH z axis, the variable added to θ.
    Revolute,
    /// Translation along the DH z axis, the variable added to d.
    Prismatic,
}

/// One link: its standard DH parameters (frame i = Rz(θ) Tz(d) Tx(a) Rx(α)) and its rigid body.
#[derive(Clone, Debug, PartialEq)]
pub struct ChainLink {
    /// The joint.
    pub joint: JointType,
    /// Link length a (m).
    pub a: f64,
    /// Link twist α (rad).
    pub alpha: f64,
    /// Link offset d (m).
    pub d: f64,
    /// Joint angle offset θ (rad).
    pub theta: f64,
    /// Mass (kg).
    pub mass: f64,
    /// Centre of mass in frame i (m).
    pub com: [f64; 3],
    /// Inertia about the centre of mass in frame i: xx, yy, zz, xy, xz, yz (kg m²).
    pub inertia: [f64; 6],
}

impl ChainLink {
    /// The same link with every length multiplied by `s` and the mass kept: the inertia about
    /// the centre of mass scales with s².
    pub fn scaled_lengths(&self, s: f64) -> ChainLink {
        ChainLink {
            a: self.a * s,
            d: self.d * s,
            com: self.com.map(|c| c * s),
            inertia: self.inertia.map(|i| i * s * s),
            ..self.clone()
        }
    }

    /// The same link with its mass, and so its inertia, multiplied by `r`.
    pub fn scaled_mass(&self, r: f64) -> ChainLink {
        ChainLink {
            mass: self.mass * r,
            inertia: self.inertia.map(|i| i * r),
            ..self.clone()
        }
    }
}

/// A serial robot of [`ChainLink`]s under gravity.
#[derive(Clone, Debug, PartialEq)]
pub struct Chain {
    /// The robot's name in the spec.
    pub name: String,
    /// Gravity in the base frame (m/s²).
    pub gravity: [f64; 3],
    /// The links from the base out.
    pub links: Vec<ChainLink>,
}

impl Chain {
    /// A four-joint spatial arm of ordinary proportions (a shoulder, an upper arm, an elbow
    /// and a wrist roll, PUMA-like, masses 8, 6, 3 and 1.5 kg), the base robot of the mass
    /// ratio and link length cases. Its centres of mass are off the joint axes and its
    /// inertias have products, so that no term of the dynamics vanishes by symmetry.
    pub fn arm() -> Chain {
        let link =
            |a: f64, alpha: f64, d: f64, mass: f64, com: [f64; 3], inertia: [f64; 6]| ChainLink {
                joint: JointType::Revolute,
                a,
                alpha,
                d,
                theta: 0.0,
                mass,
                com,
                inertia,
            };
        Chain {
            name: "stress-arm".into(),
            gravity: [0.0, 0.0, -9.81],
            links: vec![
                link(
                    0.0,
                    FRAC_PI_2,
                    0.4,
                    8.0,
                    [0.0, -0.15, 0.02],
                    [0.20, 0.15, 0.18, 0.01, -0.005, 0.008],
                ),
                link(
                    0.45,
                    0.0,
                    0.1,
                    6.0,
                    [-0.22, 0.01, 0.05],
                    [0.03, 0.25, 0.24, 0.004, 0.01, -0.002],
                ),
                link(
                    0.05,
                    FRAC_PI_2,
                    0.0,
                    3.0,
                    [0.01, -0.02, 0.1],
                    [0.04, 0.035, 0.012, -0.001, 0.002, 0.003],
                ),
                link(
                    0.0,
                    -FRAC_PI_2,
                    0.35,
                    1.5,
                    [0.0, 0.02, -0.1],
                    [0.02, 0.018, 0.01, 0.0005, -0.001, 0.001],
                ),
            ],
        }
    }

    /// A planar arm of revolute joints about parallel z axes (every α = 0), gravity along −y:
    /// link k has length `lengths[k]`, mass `masses[k]`, its centre of mass half-way along it
    /// and the inertia of a slender box about the centre (with a floor of 10⁻⁶ of its mass in
    /// m² so that a very short link still has a valid inertia).
    pub fn planar(name: &str, lengths: &[f64], masses: &[f64]) -> Chain {
        let links = lengths
            .iter()
            .zip(masses)
            .map(|(&l, &m)| {
                let across = m * 1e-4 + m * l * l / 12.0;
                ChainLink {
                    joint: JointType::Revolute,
                    a: l,
                    alpha: 0.0,
                    d: 0.0,
                    theta: 0.0,
                    mass: m,
                    com: [-l / 2.0, 0.0, 0.0],
                    inertia: [m * 1e-4, across, across, 0.0, 0.0, 0.0],
                }
            })
            .collect();
        Chain {
            name: name.into(),
            gravity: [0.0, -9.81, 0.0],
            links,
        }
    }

    /// The spec file of the robot. Numbers are written in Rust's shortest round-trip
    /// exponent form, so the model read back has exactly these `f64` values.
    pub fn to_toml(&self) -> String {
        let [gx, gy, gz] = self.gravity;
        let mut text = format!(
            "name = \"{}\"\ngravity = [{gx:e}, {gy:e}, {gz:e}]\n",
            self.name
        );
        for (i, l) in self.links.iter().enumerate() {
            let joint = match l.joint {
                JointType::Revolute => "revolute",
                JointType::Prismatic => "prismatic",
            };
            let [cx, cy, cz] = l.com;
            let [xx, yy, zz, xy, xz, yz] = l.inertia;
            text.push_str(&format!(
                "\n[[link]]\nname = \"link{}\"\njoint = \"{joint}\"\n\
                 dh = {{ a = {:e}, alpha = {:e}, d = {:e}, theta = {:e} }}\n\
                 mass = {:e}\ncom = [{cx:e}, {cy:e}, {cz:e}]\n\
                 inertia = {{ xx = {xx:e}, yy = {yy:e}, zz = {zz:e}, xy = {xy:e}, xz = {xz:e}, yz = {yz:e} }}\n",
                i + 1,
                l.a,
                l.alpha,
                l.d,
                l.theta,
                l.mass,
            ));
        }
        text
    }

    /// The robot model, through the spec reader.
    pub fn model(&self) -> Result<RobotModel, SpecError> {
        read_robot(
            Description::toml(&self.to_toml(), &format!("{}.toml", self.name)),
            &LoadOptions::default(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stress robots are valid specs with the joints they were built with, and scaling
    /// keeps them valid.
    #[test]
    fn chains_read_back_as_models() {
        let arm = Chain::arm();
        assert_eq!(arm.model().unwrap().dof(), 4);
        let tiny = Chain {
            links: arm.links.iter().map(|l| l.scaled_lengths(1e-4)).collect(),
            ..arm.clone()
        };
        assert_eq!(tiny.model().unwrap().dof(), 4);
        let light = Chain {
            links: arm.links.iter().map(|l| l.scaled_mass(1e-6)).collect(),
            ..arm
        };
        assert_eq!(light.model().unwrap().dof(), 4);
        let planar = Chain::planar("p", &[0.5, 1e-7, 0.5], &[1.0, 1e-9, 1.0]);
        assert_eq!(planar.model().unwrap().dof(), 3);
    }
}
