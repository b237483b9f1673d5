//! A kernel too large for one function is emitted in parts that pass values through a slot
//! array (rne-codegen-core's split.rs): the compiled parts compute bit for bit what the
//! kernel's program computes, operation by operation.

mod common;

use common::state;
use rne_codegen_core::{generate_from_path, GenerationOptions, Kernel, Scene};
use rne_interpreted::{Interpreted, StateRef};
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};

rne_codegen::derive_dynamics! {
    /// A 20-joint chain: its Coriolis matrix is split, its potential energy is not.
    mod chain {
        robot: "fixtures/robots/chain-20.toml",
        outputs: [coriolis_matrix, potential_energy],
    }
}

rne_codegen::derive_dynamics! {
    /// The same Coriolis kernel, generic over the scalar and with the parameters at run time:
    /// its parts take them too.
    mod chain_generic {
        robot: "fixtures/robots/chain-20.toml",
        outputs: [coriolis_matrix],
        scalar: generic,
        parameters: runtime,
    }
}

const FIXTURE: &str = "fixtures/robots/chain-20.toml";

#[test]
fn the_large_kernels_of_the_chain_are_emitted_in_parts() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(FIXTURE);
    let emitted = |kernel: Kernel| {
        let options = GenerationOptions {
            outputs: vec![kernel],
            ..GenerationOptions::default()
        };
        let module =
            generate_from_path(&path, &Scene::default(), &options).expect("the fixture generates");
        module.source
    };
    assert!(
        emitted(Kernel::CoriolisMatrix).contains("mod part1"),
        "C is split"
    );
    assert!(
        !emitted(Kernel::PotentialEnergy).contains("mod part0"),
        "V is one function"
    );
}

#[test]
fn split_kernels_equal_their_programs_bit_for_bit() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(FIXTURE);
    let model =
        read_robot(Description::file(&path), &LoadOptions::default()).expect("the fixture loads");
    let interpreted = Interpreted::new(&model);
    let mut rng = common::rng(0x5eed_5917);
    let bits = |v: Vec<f64>| v.into_iter().map(f64::to_bits).collect::<Vec<_>>();
    for _ in 0..20 {
        let (q, qd, _) = state(&mut rng, chain::NDOF);
        let (q, qd): ([f64; 20], [f64; 20]) = (q.try_into().unwrap(), qd.try_into().unwrap());
        assert_eq!(
            bits(chain::coriolis_matrix(&q, &qd).concat()),
            bits(
                interpreted
                    .evaluate(
                        Kernel::CoriolisMatrix,
                        StateRef {
                            q: &q,
                            qd: &qd,
                            qdd: &[],
                            tau: &[]
                        }
                    )
                    .unwrap()
            ),
            "C"
        );
        let generic = chain_generic::coriolis_matrix(&chain_generic::Params::default(), &q, &qd);
        assert_eq!(
            bits(generic.concat()),
            bits(chain::coriolis_matrix(&q, &qd).concat()),
            "C, generic with runtime parameters"
        );
        assert_eq!(
            chain::potential_energy(&q).to_bits(),
            interpreted
                .evaluate(
                    Kernel::PotentialEnergy,
                    StateRef {
                        q: &q,
                        qd: &[],
                        qdd: &[],
                        tau: &[]
                    }
                )
                .unwrap()[0]
                .to_bits(),
            "V"
        );
    }
}
