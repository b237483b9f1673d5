//! Small random robots written as robot files, for the generator: trees of up to four moving
//! joints (revolute, prismatic, continuous) and fixed links, in every frame convention of the
//! TOML spec or as a URDF, with masses and lengths that are ordinary, zero, tiny or large,
//! massless links, mimic joints, friction, armature, and fixed or floating bases.

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rne_symbolic::spec::RobotFormat;

use crate::mutate::pick;

/// A random robot file of `format` (its text).
pub fn random_robot(rng: &mut ChaCha8Rng, format: RobotFormat) -> String {
    let links = random_links(rng);
    match format {
        RobotFormat::Toml => toml(rng, &links),
        RobotFormat::Urdf => urdf(rng, &links),
    }
}

/// The joint of a random link.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Kind {
    Revolute,
    Prismatic,
    Fixed,
}

/// A random link: its parent (an earlier link, `None` for the base), its joint, its joint
/// variable's number among the moving joints, and the joint it mimics.
#[derive(Clone, Debug)]
struct RandomLink {
    parent: Option<usize>,
    kind: Kind,
    variable: usize,
    mimic: Option<usize>,
}

fn random_links(rng: &mut ChaCha8Rng) -> Vec<RandomLink> {
    let count = rng.gen_range(1..=5);
    let mut links: Vec<RandomLink> = Vec::with_capacity(count);
    let mut moving = 0;
    for i in 0..count {
        let kind = match rng.gen_range(0..10) {
            0..=5 => Kind::Revolute,
            6..=7 => Kind::Prismatic,
            _ => Kind::Fixed,
        };
        let kind = if moving == 4 { Kind::Fixed } else { kind };
        let parent = (i > 0 && rng.gen_bool(0.8)).then(|| rng.gen_range(0..i));
        let mimic = (kind != Kind::Fixed && moving > 0 && rng.gen_bool(0.15))
            .then(|| rng.gen_range(1..=moving));
        if kind != Kind::Fixed {
            moving += 1;
        }
        links.push(RandomLink {
            parent,
            kind,
            variable: moving,
            mimic,
        });
    }
    links
}

/// A length, mass or moment: mostly ordinary, sometimes zero, tiny or large.
fn magnitude(rng: &mut ChaCha8Rng, ordinary: f64) -> f64 {
    match rng.gen_range(0..20) {
        0 => 0.0,
        1 => 1e-9,
        2 => 1e4 * ordinary,
        _ => rng.gen_range(0.05..=1.0) * ordinary,
    }
}

fn signed(rng: &mut ChaCha8Rng, ordinary: f64) -> f64 {
    let m = magnitude(rng, ordinary);
    if rng.gen_bool(0.5) {
        -m
    } else {
        m
    }
}

fn vector(rng: &mut ChaCha8Rng, ordinary: f64) -> [f64; 3] {
    [0; 3].map(|_| {
        if rng.gen_bool(0.3) {
            0.0
        } else {
            signed(rng, ordinary)
        }
    })
}

/// A non-zero axis, often a coordinate axis, sometimes not of unit length.
fn axis(rng: &mut ChaCha8Rng) -> [f64; 3] {
    let mut axis = [0.0; 3];
    if rng.gen_bool(0.6) {
        axis[rng.gen_range(0..3)] = *pick(rng, &[1.0, -1.0, 2.5]);
    } else {
        axis = [0; 3].map(|_| rng.gen_range(-1.0..=1.0));
        axis[rng.gen_range(0..3)] += 1.5;
    }
    axis
}

/// Mass and principal moments (x + y, y + z, z + x) · scale: positive definite within the
/// triangle inequality, or all zero.
fn inertials(rng: &mut ChaCha8Rng) -> (f64, [f64; 3]) {
    let mass = magnitude(rng, 5.0);
    let raw = [0; 3].map(|_| rng.gen_range(0.01..=1.0));
    let scale = mass / 50.0;
    let moments = [raw[0] + raw[1], raw[1] + raw[2], raw[2] + raw[0]].map(|m| m * scale);
    (mass, moments)
}

fn list(values: [f64; 3]) -> String {
    format!("[{:?}, {:?}, {:?}]", values[0], values[1], values[2])
}

fn toml(rng: &mut ChaCha8Rng, links: &[RandomLink]) -> String {
    let mut out = String::from("name = \"random\"\n");
    if rng.gen_bool(0.3) {
        out.push_str("base = \"floating\"\n");
    }
    out.push_str(&format!("gravity = {}\n", list(vector(rng, 9.81))));
    for (i, link) in links.iter().enumerate() {
        out.push_str(&format!("\n[[link]]\nname = \"l{i}\"\n"));
        if let Some(p) = link.parent {
            out.push_str(&format!("parent = \"l{p}\"\n"));
        } else if i > 0 {
            out.push_str("parent = \"base\"\n");
        }
        out.push_str(&toml_joint(rng, link));
        let (mass, moments) = inertials(rng);
        out.push_str(&format!(
            "mass = {mass:?}\ncom = {}\n",
            list(vector(rng, 0.2))
        ));
        out.push_str(&format!(
            "inertia = {{ xx = {:?}, yy = {:?}, zz = {:?} }}\ntriangle_inequality = false\n",
            moments[0], moments[1], moments[2]
        ));
        if link.kind != Kind::Fixed && rng.gen_bool(0.2) {
            let [v, c, o] = [0; 3].map(|_| magnitude(rng, 1.0));
            out.push_str(&format!(
                "friction = {{ viscous = {v:?}, coulomb = {c:?}, offset = {o:?} }}\narmature = {:?}\n",
                magnitude(rng, 0.1)
            ));
        }
    }
    out
}

/// A link's joint in a random convention: origin and axis, DH, modified DH, or rotation and
/// position.
fn toml_joint(rng: &mut ChaCha8Rng, link: &RandomLink) -> String {
    let q = format!("q{}", link.variable);
    let [a, d, alpha] = [0; 3].map(|_| signed(rng, 0.5));
    let mut out = match link.kind {
        Kind::Fixed => {
            return format!(
                "joint = \"fixed\"\norigin = {{ xyz = {}, rpy = {} }}\n",
                list(vector(rng, 0.3)),
                list(vector(rng, 3.0))
            )
        }
        Kind::Revolute => format!("joint = \"revolute\"\nq = \"{q}\"\n"),
        Kind::Prismatic => format!("joint = \"prismatic\"\nq = \"{q}\"\n"),
    };
    let revolute = link.kind == Kind::Revolute;
    out.push_str(&match rng.gen_range(0..4) {
        0 => format!(
            "origin = {{ xyz = {}, rpy = {} }}\naxis = {}\n",
            list(vector(rng, 0.3)),
            list(vector(rng, 3.0)),
            list(axis(rng))
        ),
        1 if revolute => format!("dh = {{ d = {d:?}, a = {a:?}, alpha = {alpha:?} }}\n"),
        1 => format!("dh = {{ theta = {d:?}, a = {a:?}, alpha = {alpha:?} }}\n"),
        2 if revolute => format!("mdh = {{ d = {d:?}, a = {a:?}, alpha = {alpha:?} }}\n"),
        2 => format!("mdh = {{ theta = {d:?}, a = {a:?}, alpha = {alpha:?} }}\n"),
        _ if revolute => {
            format!("rotation = \"Rx({alpha:?}) * Rz({q})\"\nposition = [{a:?}, 0, {d:?}]\n")
        }
        _ => format!("rotation = \"Ry({alpha:?})\"\nposition = [{a:?}, 0, \"{q} + {d:?}\"]\n"),
    });
    if let Some(leader) = link.mimic {
        out.push_str(&format!(
            "mimic = {{ joint = \"q{leader}\", multiplier = {:?}, offset = {:?} }}\n",
            signed(rng, 2.0),
            signed(rng, 0.5)
        ));
    }
    out
}

fn urdf(rng: &mut ChaCha8Rng, links: &[RandomLink]) -> String {
    let mut out =
        String::from("<?xml version=\"1.0\"?>\n<robot name=\"random\">\n  <link name=\"root\"/>\n");
    for (i, link) in links.iter().enumerate() {
        out.push_str(&urdf_link(rng, i));
        let parent = link.parent.map_or("root".to_owned(), |p| format!("l{p}"));
        let kind = match link.kind {
            Kind::Fixed => "fixed",
            Kind::Prismatic => "prismatic",
            Kind::Revolute if rng.gen_bool(0.5) => "continuous",
            Kind::Revolute => "revolute",
        };
        out.push_str(&format!(
            "  <joint name=\"q{}\" type=\"{kind}\">\n    <parent link=\"{parent}\"/>\n    <child link=\"l{i}\"/>\n",
            if link.kind == Kind::Fixed { format!("fixed{i}") } else { link.variable.to_string() }
        ));
        let xyz = words(vector(rng, 0.3));
        let rpy = words(vector(rng, 3.0));
        out.push_str(&format!("    <origin xyz=\"{xyz}\" rpy=\"{rpy}\"/>\n"));
        if link.kind != Kind::Fixed {
            out.push_str(&format!("    <axis xyz=\"{}\"/>\n", words(axis(rng))));
            if let Some(leader) = link.mimic {
                let (m, o) = (signed(rng, 2.0), signed(rng, 0.5));
                out.push_str(&format!(
                    "    <mimic joint=\"q{leader}\" multiplier=\"{m:?}\" offset=\"{o:?}\"/>\n"
                ));
            }
            if rng.gen_bool(0.2) {
                let (d, f) = (magnitude(rng, 1.0), magnitude(rng, 1.0));
                out.push_str(&format!(
                    "    <dynamics damping=\"{d:?}\" friction=\"{f:?}\"/>\n"
                ));
            }
        }
        out.push_str("  </joint>\n");
    }
    out.push_str("</robot>\n");
    out
}

fn urdf_link(rng: &mut ChaCha8Rng, i: usize) -> String {
    if rng.gen_bool(0.1) {
        return format!("  <link name=\"l{i}\"/>\n");
    }
    let (mass, [xx, yy, zz]) = inertials(rng);
    format!(
        "  <link name=\"l{i}\">\n    <inertial>\n      <origin xyz=\"{}\" rpy=\"{}\"/>\n      <mass value=\"{mass:?}\"/>\n      <inertia ixx=\"{xx:?}\" ixy=\"0\" ixz=\"0\" iyy=\"{yy:?}\" iyz=\"0\" izz=\"{zz:?}\"/>\n    </inertial>\n  </link>\n",
        words(vector(rng, 0.2)),
        words(vector(rng, 3.0))
    )
}

fn words(values: [f64; 3]) -> String {
    format!("{:?} {:?} {:?}", values[0], values[1], values[2])
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rne_symbolic::spec::LoadOptions;
    use rne_symbolic::{read_robot, Description};

    /// Nearly every random robot loads (a robot whose moving subtree is massless, or whose
    /// values are extreme, may be rejected; none may panic), and each is reproducible.
    #[test]
    fn random_robots_load_and_replay() {
        for format in [RobotFormat::Toml, RobotFormat::Urdf] {
            let mut loaded = 0;
            for seed in 0..200 {
                let text = random_robot(&mut ChaCha8Rng::seed_from_u64(seed), format);
                assert_eq!(
                    text,
                    random_robot(&mut ChaCha8Rng::seed_from_u64(seed), format)
                );
                let name = match format {
                    RobotFormat::Toml => "random.toml",
                    RobotFormat::Urdf => "random.urdf",
                };
                match read_robot(
                    Description::text(&text, format, name),
                    &LoadOptions::default(),
                ) {
                    Ok(model) => {
                        loaded += 1;
                        assert!(model.dof() <= 4);
                    }
                    Err(e) => assert!(e.to_string().starts_with(name), "{e}"),
                }
            }
            assert!(loaded >= 180, "{format:?}: {loaded} of 200 loaded");
        }
    }
}
