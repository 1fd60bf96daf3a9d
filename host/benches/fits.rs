//! Every model at 6, 24 and 100 positions (criterion): `cargo bench -p accelcal --bench fits`.

use accelcal::fit::Model;
use accelcal::fit::{self, FitOptions, ModelChoice, RICHEST_FIRST};
use accelcal::sim::synthetic::random_positions;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};

fn fits(c: &mut Criterion) {
    let mut group = c.benchmark_group("fit");
    for positions in [6, 24, 100] {
        for model in RICHEST_FIRST {
            let with_references = matches!(model, Model::ReferenceNorm12 | Model::Linear12 | Model::SixPosition);
            let dataset = random_positions(7, positions, 1e-4, with_references);
            let choice = ModelChoice::Only(model);
            if let Err(error) = fit::fit(&dataset, choice, &FitOptions::default()) {
                println!("{} at {positions} positions: not supported ({error})", model.name());
                continue;
            }
            group.bench_with_input(BenchmarkId::new(model.name(), positions), &dataset, |b, dataset| {
                b.iter(|| fit::fit(dataset, choice, &FitOptions::default()))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, fits);
criterion_main!(benches);
