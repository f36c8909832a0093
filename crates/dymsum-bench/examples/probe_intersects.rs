use dymsum::query::ConvexPair;
use dymsum_bench::contact::contact_motion;
use dymsum_bench::load;
fn main() {
    let name = std::env::args().nth(1).unwrap_or("box".into());
    let (a, b) = if name == "box" {
        (load("box:1,2,3"), load("box:2,1,1"))
    } else {
        (load("gs4"), load("ellipse"))
    };
    let pair = ConvexPair::new(&a, &b).unwrap();
    let poses = contact_motion(&a, &b, 500.0, 1000);
    let what = std::env::args().nth(2).unwrap_or("i".into());
    let t = std::time::Instant::now();
    for _ in 0..50 {
        for &(pa, pb) in &poses {
            if what == "i" {
                std::hint::black_box(pair.intersects(pa, pb).unwrap());
            } else {
                std::hint::black_box(pair.query(pa, pb).unwrap());
            }
        }
    }
    println!("{:.2} µs", t.elapsed().as_secs_f64() * 1e6 / 50000.0);
}
