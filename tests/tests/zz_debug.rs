use lambert_estimator::goodness_of_fit::Grid;
use lambert_sampling::catalog::Precision;
use lambert_tests::*;
#[test]
fn dbg() {
    let case = direction_cases()
        .into_iter()
        .find(|c| c.label == "triangle area grazing")
        .unwrap();
    let warp = case.spec.build(Precision::F64).unwrap();
    let grid = Grid::new(&binning_for(&case.spec)).unwrap();
    let mut seq = lambert_sampling::Independent::new(1);
    use lambert_sampling::SampleSequence;
    let mut k = 0;
    for i in 0..400000u64 {
        seq.start_sample(i);
        let s = warp.sample(seq.next_2d());
        if grid.locate(s.direction) == 244 && k < 5 {
            k += 1;
            println!(
                "w={} pdf_s={} pdf={} cell={:?}",
                s.direction,
                s.pdf,
                warp.pdf(s.direction),
                grid.cell(244)
            );
        }
    }
    println!("cap {:?}", case.spec.bounding_cap());
}
