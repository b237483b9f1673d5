//! Base parameters (`rne show MODEL --what base-parameters`, `rne identify`): their number is
//! the numeric rank of the stacked regressor for every built-in robot and for random robots,
//! Y_b π_b reproduces the torques, the planar elbow's are the thesis's grouping, and the
//! PUMA 560's count is the published one.

mod common;

use common::numeric_rank;
use nalgebra::DMatrix;
use proptest::prelude::*;
use rne_identify::BaseSet;
use rne_models::builtin::{RobotSource, BUILTIN_ROBOTS};
use rne_reference::Reference;
use rne_symbolic::model::NumericFriction;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::NumericModel;
use rne_symbolic::{read_robot, Description};

/// Seeded states, distinct from the ones `BaseSet::find` uses.
fn states(nv: usize, count: usize, seed: u64) -> Vec<(Vec<f64>, Vec<f64>, Vec<f64>)> {
    let mut x = seed;
    let mut next = move || {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    (0..count)
        .map(|_| {
            let q = (0..nv).map(|_| 3.0 * next()).collect();
            let v = (0..nv).map(|_| 2.0 * next()).collect();
            let a = (0..nv).map(|_| 4.0 * next()).collect();
            (q, v, a)
        })
        .collect()
}

/// The regressor stacked over `count` states.
fn stacked(reference: &mut Reference, count: usize, seed: u64) -> DMatrix<f64> {
    let (nv, p) = (reference.nv(), reference.parameter_count());
    let mut w = DMatrix::zeros(count * nv, p);
    for (s, (q, v, a)) in states(nv, count, seed).iter().enumerate() {
        let y = reference.regressor(q, v, a).expect("state sizes");
        w.view_mut((s * nv, 0), (nv, p)).copy_from(&y);
    }
    w
}

/// The base parameters' count equals the rank, and Y_b π_b = τ at fresh states.
fn check(model: &NumericModel, name: &str) -> usize {
    let mut reference = Reference::new(model).with_friction(true);
    let base = BaseSet::find(&mut reference).expect("base parameters");
    let w = stacked(&mut reference, 60, 0xfeed);
    assert_eq!(
        base.len(),
        numeric_rank(&w),
        "{name}: base parameters vs rank"
    );
    let pi_b = nalgebra::DVector::from_vec(base.model_values());
    for (q, v, a) in states(reference.nv(), 50, 0xbeef) {
        let tau = reference.inverse_dynamics(&q, &v, &a).expect("sizes");
        let predicted = base
            .base_regressor(&mut reference, &q, &v, &a)
            .expect("sizes")
            * &pi_b;
        let error = (&predicted - &tau).amax() / tau.amax().max(1e-300);
        assert!(error < 1e-12, "{name}: Y_b π_b vs τ, relative {error:e}");
    }
    base.len()
}

fn builtin(name: &str) -> NumericModel {
    RobotSource::resolve(name)
        .load(&LoadOptions::default())
        .expect("built-in robot")
        .to_numeric()
}

#[test]
fn every_builtin_robot_has_as_many_base_parameters_as_the_regressor_has_rank() {
    for robot in BUILTIN_ROBOTS {
        check(&builtin(robot.name), robot.name);
    }
}

/// With friction (f_v, f_c, offset) and armature on every joint of the IRB 140: still the
/// rank, and the joint parameters add 3 + 1 each except the armatures of joints 1 and 2.
/// Link 1 turns about the vertical axis 1 only, so its inertia about that axis and the rotor
/// of joint 1 both add ½ x q̇1² to the kinetic energy and nothing to the potential; link 2's
/// angular velocity along axis 2 is q̇2 alone (axis 1 is perpendicular to it), so its inertia
/// about axis 2 and the rotor of joint 2 both add ½ x q̇2². Each pair is one base parameter.
#[test]
fn friction_and_armature_columns_keep_count_and_rank_equal() {
    let plain = check(&builtin("irb140"), "irb140");
    let mut model = builtin("irb140");
    for link in model.links.iter_mut().filter(|l| l.joint.is_some()) {
        link.friction = Some(NumericFriction {
            viscous: 0.5,
            coulomb: 1.0,
            offset: -0.1,
        });
        link.armature = Some(0.02);
    }
    let with_joints = check(&model, "irb140 with friction and armature");
    assert_eq!(with_joints, plain + 6 * 4 - 2);
}

/// PUMA 560, the 60 standard inertial parameters (10 per link; no motor inertia, no
/// friction): 36 base parameters. M. Gautier, "Numerical calculation of the base inertial
/// parameters of robots", Journal of Robotic Systems 8(4):485–506, 1991, applies the method to
/// this robot (its text could not be read here: docs/identification.md). The count follows
/// from Gautier and Khalil's regrouping rules ("Direct calculation of minimum set of inertial
/// parameters of serial robots", IEEE Trans. Robotics and Automation 6(3), 1990): each
/// revolute link j regroups YY_j, MZ_j and M_j onto its parent (60 − 6·3 = 42), and of link 1,
/// turning about the vertical, only ZZR_1 remains (42 − 6 = 36).
#[test]
fn puma560_has_the_published_36_base_parameters() {
    assert_eq!(check(&builtin("puma560"), "puma560"), 36);
}

/// With a rotor inertia on every joint (the model Khalil and Dombre use for the Stäubli RX-90,
/// the PUMA's geometry) four more: I_a1 acts only as ZZR_1 does (½ x q̇1²), and I_a2 as link 2's
/// inertia about axis 2, along which its angular velocity is q̇2 alone (axis 1 ⟂ axis 2).
#[test]
fn puma560_with_rotor_inertias_has_40_base_parameters() {
    let mut model = builtin("puma560");
    for link in model.links.iter_mut().filter(|l| l.joint.is_some()) {
        link.armature = Some(1e-3);
    }
    assert_eq!(check(&model, "puma560 with rotor inertias"), 40);
}

/// The planar elbow (thesis chapter 4, frames at the link ends, so each body's standard
/// parameters are about its joint axis): the base parameters are the groups its M (4.45)
/// and g (4.47) show, m1 lc1 + m2 l1, I1 + m1 lc1² + m2 l1², m2 lc2 and I2 + m2 lc2², with the
/// first moments off the link axis (zero for the thesis's links) beside them; the
/// coefficients print as the exact l1 = 0.3 and l1² = 0.09 of table 6.1.
#[test]
fn the_planar_elbows_base_parameters_are_the_thesiss_groups() {
    let mut reference = Reference::new(&builtin("planar-elbow"));
    let base = BaseSet::find(&mut reference).expect("base parameters");
    let printed: Vec<String> = (0..base.len()).map(|b| base.combination(b)).collect();
    assert_eq!(
        printed,
        [
            "m1·cx1 + 0.3·m2",
            "m1·cy1",
            "I1zz + 0.09·m2",
            "m2·cx2",
            "m2·cy2",
            "I2zz"
        ]
    );
    // Table 6.1: m = 15 kg, l = 0.3 m, steel boxes of width w = sqrt(m / (rho l)).
    let (m, l, lc) = (15.0, 0.3, 0.15);
    let w2 = m / (7850.0 * l);
    let inertia = m * (l * l + w2) / 12.0;
    let thesis = [
        m * lc + m * l,
        0.0,
        inertia + m * lc * lc + m * l * l,
        m * lc,
        0.0,
        inertia + m * lc * lc,
    ];
    for (b, (value, expected)) in base.model_values().iter().zip(thesis).enumerate() {
        assert!(
            (value - expected).abs() < 1e-12 * expected.abs().max(1.0),
            "b{}: {value} vs the thesis's {expected}",
            b + 1
        );
    }
}

/// A random robot (found by the property test below) one of whose regrouping coefficients,
/// −0.558367000047, lies a relative 8e-11 from the short decimal −0.558367: snapping it to the
/// decimal moved Y_b π_b off τ by a relative 2e-12. The coefficients keep their digits unless
/// they are within rounding of a short number, and Y_b π_b = τ holds.
#[test]
fn a_coefficient_near_a_short_decimal_is_not_rounded_to_it() {
    let model = read_robot(
        Description::toml(&near_short_decimal(), "near_short_decimal.toml"),
        &LoadOptions::default(),
    )
    .expect("valid spec")
    .to_numeric();
    let base = BaseSet::find(&mut Reference::new(&model).with_friction(true)).expect("base");
    let near: Vec<f64> = base
        .parameters
        .k
        .iter()
        .flatten()
        .copied()
        .filter(|k| (k + 0.558367).abs() < 1e-9)
        .collect();
    assert!(
        !near.is_empty() && near.iter().all(|&k| k != -0.558367),
        "the coefficient near −0.558367 keeps its digits: {near:?}"
    );
    check(&model, "near_short_decimal");
}

/// That robot's links (all revolute) and gravity, as the property test drew them.
fn near_short_decimal() -> String {
    let link = |dh: [f64; 4], mass: f64, com: [f64; 3], moments: [f64; 3]| RandomLink {
        prismatic: false,
        dh,
        mass,
        com,
        moments,
    };
    let links = [
        link(
            [0.0, 0.4211027448891881, 0.0, 0.0],
            0.5,
            [
                0.032064087253233335,
                -0.1054003829871511,
                -0.03518275008049578,
            ],
            [0.8389289627482239, 0.47238796651695136, 0.4747887998699543],
        ),
        link(
            [
                1.0465091463688474,
                -0.13964614780914963,
                -0.2570214664020444,
                -0.031000701191241584,
            ],
            5.181799601800871,
            [
                0.1906349232937261,
                -0.0007417617418634374,
                0.17807796117317107,
            ],
            [0.5642920668657727, 0.7621552823103885, 0.7660236397424427],
        ),
        link(
            [
                1.3178309264948755,
                1.2960008932444702,
                -1.4062700502679832,
                -0.06478557497975322,
            ],
            8.946425655273307,
            [
                -0.11887881903118006,
                0.02908505189858652,
                -0.049644242688349424,
            ],
            [0.7950846613549976, 0.550480775795936, 0.6083277641747489],
        ),
        link(
            [
                1.4054025204651939,
                0.5930121722737233,
                -0.42375889971939357,
                -1.4731275330167315,
            ],
            2.0091284387669996,
            [
                0.14322540386830535,
                -0.19914122556416555,
                0.008538053416235756,
            ],
            [0.515873187534388, 0.2597361321838153, 0.4450884091538755],
        ),
    ];
    spec(
        &links,
        [-4.0065889799090195, -6.156644244531412, 8.097684517121493],
    )
}

/// One random link in standard DH with a random inertia.
#[derive(Clone, Debug)]
struct RandomLink {
    prismatic: bool,
    dh: [f64; 4],
    mass: f64,
    com: [f64; 3],
    moments: [f64; 3],
}

fn link() -> impl Strategy<Value = RandomLink> {
    (
        prop::bool::weighted(0.3),
        prop::array::uniform4(-1.5..1.5f64),
        0.5..10.0f64,
        prop::array::uniform3(-0.2..0.2f64),
        prop::array::uniform3(0.01..0.5f64),
    )
        .prop_map(|(prismatic, dh, mass, com, raw)| RandomLink {
            prismatic,
            dh,
            mass,
            com,
            // (x + y, y + z, z + x) of positive x, y, z obey the triangle inequality.
            moments: [raw[0] + raw[1], raw[1] + raw[2], raw[2] + raw[0]],
        })
}

fn spec(links: &[RandomLink], gravity: [f64; 3]) -> String {
    let mut text = format!(
        "name = \"random\"\ngravity = [{}, {}, {}]\n",
        gravity[0], gravity[1], gravity[2]
    );
    for (i, l) in links.iter().enumerate() {
        let [a, alpha, d, theta] = l.dh;
        text += &format!(
            "[[link]]\nname = \"l{i}\"\njoint = \"{}\"\ndh = {{ a = {a}, alpha = {alpha}, d = {d}, theta = {theta} }}\nmass = {}\ncom = [{}, {}, {}]\ninertia = {{ xx = {}, yy = {}, zz = {} }}\n",
            if l.prismatic { "prismatic" } else { "revolute" },
            l.mass, l.com[0], l.com[1], l.com[2], l.moments[0], l.moments[1], l.moments[2]
        );
    }
    text
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 8, ..ProptestConfig::default() })]

    /// Random serial robots of 1–5 revolute or prismatic joints in random DH geometry:
    /// as many base parameters as the stacked regressor's numeric rank, and Y_b π_b = τ.
    #[test]
    fn random_robots_have_as_many_base_parameters_as_the_regressor_has_rank(
        links in prop::collection::vec(link(), 1..=5),
        gravity in prop::array::uniform3(-10.0..10.0f64),
    ) {
        let text = spec(&links, gravity);
        let model = read_robot(Description::toml(&text, "random.toml"), &LoadOptions::default()).expect("valid spec");
        check(&model.to_numeric(), &text);
    }
}
