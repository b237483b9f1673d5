//! A kernel too large for one function is emitted in parts that pass values through a slot
//! array (rne-codegen-core's split.rs): the compiled parts compute bit for bit what the
//! kernel's program computes, operation by operation.

mod common;

use common::state;
use rne_codegen_core::{generate_from_path, Kernel, Scene};
use rne_models::interpreted::Interpreted;
use rne_models::kernels::Kernels;
use rne_symbolic::spec::{load_robot, LoadOptions};

rne_codegen::derive_dynamics! {
    /// A 20-joint chain: its Coriolis matrix is split, its mass matrix is not.
    mod chain {
        robot: "fixtures/robots/chain-20.toml",
        outputs: [coriolis_matrix, forward_dynamics, mass_matrix],
    }
}

const FIXTURE: &str = "fixtures/robots/chain-20.toml";

#[test]
fn the_large_kernels_of_the_chain_are_emitted_in_parts() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(FIXTURE);
    let emitted = |kernel: Kernel| {
        let scene = Scene {
            outputs: vec![kernel],
            ..Scene::default()
        };
        let module = generate_from_path(&path, &scene).expect("the fixture generates");
        module.items.to_string()
    };
    assert!(
        emitted(Kernel::CoriolisMatrix).contains("mod part1"),
        "C is split"
    );
    assert!(
        !emitted(Kernel::MassMatrix).contains("mod part0"),
        "M is one function"
    );
}

#[test]
fn split_kernels_equal_their_programs_bit_for_bit() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(FIXTURE);
    let model = load_robot(&path, &LoadOptions::default()).expect("the fixture loads");
    let interpreted = Interpreted::new(&model);
    let mut rng = common::rng(0x5eed_5917);
    let bits = |v: Vec<f64>| v.into_iter().map(f64::to_bits).collect::<Vec<_>>();
    for _ in 0..20 {
        let (q, qd, tau) = state(&mut rng, chain::NDOF);
        let (q, qd, tau): ([f64; 20], [f64; 20], [f64; 20]) = (
            q.try_into().unwrap(),
            qd.try_into().unwrap(),
            tau.try_into().unwrap(),
        );
        assert_eq!(
            bits(chain::coriolis_matrix(&q, &qd).concat()),
            bits(interpreted.coriolis_matrix(&q, &qd).unwrap().concat()),
            "C"
        );
        assert_eq!(
            bits(chain::forward_dynamics(&q, &qd, &tau).to_vec()),
            bits(interpreted.forward_dynamics(&q, &qd, &tau).unwrap()),
            "FD"
        );
        assert_eq!(
            bits(chain::mass_matrix(&q).concat()),
            bits(interpreted.mass_matrix(&q).unwrap().concat()),
            "M"
        );
    }
}
