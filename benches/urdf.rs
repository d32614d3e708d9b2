//! Cost of reading a robot: the Panda's URDF (`robots/panda.urdf`, 7
//! joints, 7 capsules) parsed, its chain taken and its volumes made
//! (issue 40's goal: at most 5 ms natively).
//!
//! `cargo bench --bench urdf`

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use redundant_ik::urdf::volume;
use redundant_ik::urdf::{Urdf, UrdfChain};

fn read_panda(c: &mut Criterion) {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/panda.urdf"))
        .expect("robots/panda.urdf");
    c.bench_function("urdf/panda: parse, chain, volumes", |b| {
        b.iter(|| {
            let urdf = Urdf::parse(black_box(&text)).unwrap();
            let chain = UrdfChain::new(&urdf, None, None).unwrap();
            volume::volumes(&urdf, &chain, &|_| None, 0.05)
        })
    });
}

criterion_group!(benches, read_panda);
criterion_main!(benches);
