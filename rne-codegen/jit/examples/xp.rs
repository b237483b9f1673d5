use rne_codegen_core::{GenerationOptions, Kernel, Scene};
use rne_jit::{JitModel, State, Tier};
use std::time::Instant;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = &args[1];
    let variants: Vec<&str> = args[2..].iter().map(|s| s.as_str()).collect();
    let kernels = vec![
        Kernel::InverseDynamics,
        Kernel::MassMatrix,
        Kernel::ForwardDynamics,
        Kernel::InverseDynamicsDerivatives,
        Kernel::ForwardDynamicsDerivatives,
    ];
    let options = GenerationOptions {
        outputs: kernels.clone(),
        ..GenerationOptions::default()
    };
    let mut models = Vec::new();
    for v in &variants {
        for kv in v.split(',') {
            if let Some((k, val)) = kv.split_once('=') {
                std::env::set_var(k, val);
            }
        }
        let t = Instant::now();
        let m = JitModel::compile_at(
            &rne_codegen_core::read_robot(path.as_ref(), path, &Scene::default(), &options)
                .unwrap(),
            &Scene::default(),
            &options,
            path,
            if std::env::var("XP_TIER").as_deref() == Ok("opt") {
                Tier::Optimized
            } else {
                Tier::Fast
            },
        )
        .unwrap();
        eprintln!("{v}: compile {:.1} ms", t.elapsed().as_secs_f64() * 1e3);
        for kv in v.split(',') {
            if let Some((k, _)) = kv.split_once('=') {
                std::env::remove_var(k);
            }
        }
        models.push(m);
    }
    let n = models[0].nq();
    let nv = models[0].nv();
    let mut seed = 1u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    let states: Vec<(Vec<f64>, Vec<f64>, Vec<f64>)> = (0..64)
        .map(|_| {
            (
                (0..n).map(|_| rnd()).collect(),
                (0..nv).map(|_| rnd()).collect(),
                (0..nv).map(|_| rnd()).collect(),
            )
        })
        .collect();
    for &k in &kernels {
        let mut times = vec![Vec::new(); models.len()];
        let mut out = vec![0.0; models[0].output_len(k).unwrap()];
        for _round in 0..31 {
            for (i, m) in models.iter().enumerate() {
                let t = Instant::now();
                for _ in 0..10 {
                    for (q, qd, x) in &states {
                        m.evaluate(
                            k,
                            State {
                                q,
                                qd,
                                qdd: x,
                                tau: x,
                            },
                            &mut out,
                        )
                        .unwrap();
                    }
                }
                times[i].push(t.elapsed().as_secs_f64() * 1e9 / 640.0);
            }
        }
        let med = |v: &mut Vec<f64>| {
            v.sort_by(|a, b| a.partial_cmp(b).unwrap());
            v[v.len() / 2]
        };
        let base = med(&mut times[0].clone());
        let line: Vec<String> = times
            .iter_mut()
            .map(|t| {
                let m = med(t);
                format!("{:.0} ({:.2})", m, m / base)
            })
            .collect();
        println!("{:<32} {}", k.name(), line.join("  "));
    }
}
