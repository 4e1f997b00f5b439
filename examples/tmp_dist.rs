#[path = "../benches/fill_rate/workload.rs"]
mod workload;
fn main() {
    let tris = workload::triangles(workload::SizeClass::Small);
    let mut hist = std::collections::BTreeMap::new();
    let mut n8 = 0;
    for t in &tris {
        let xs = t.positions.map(|p| p.0.to_bits());
        let ys = t.positions.map(|p| p.1.to_bits());
        let w = xs.iter().max().unwrap() - xs.iter().min().unwrap();
        let h = ys.iter().max().unwrap() - ys.iter().min().unwrap();
        if w < 2048 && h < 2048 {
            n8 += 1;
        }
        *hist.entry(((w + 255) / 256, (h + 255) / 256)).or_insert(0) += 1;
    }
    println!("{} of {} under 8x8 px", n8, tris.len());
    println!("{:?}", hist);
}
