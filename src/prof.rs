use std::sync::Mutex;
use std::time::Instant;
static T: Mutex<Vec<(&'static str, f64, usize)>> = Mutex::new(Vec::new());
pub struct Guard(&'static str, Instant);
impl Drop for Guard {
    fn drop(&mut self) {
        let dt = self.1.elapsed().as_secs_f64();
        let mut t = T.lock().unwrap();
        if let Some(e) = t.iter_mut().find(|e| e.0 == self.0) {
            e.1 += dt;
            e.2 += 1;
        } else {
            t.push((self.0, dt, 1));
        }
    }
}
pub fn g(name: &'static str) -> Guard {
    Guard(name, Instant::now())
}
pub fn dump() {
    if std::env::var("TRIBO_PROF").is_err() {
        return;
    }
    let mut t = T.lock().unwrap();
    for e in t.iter() {
        eprintln!("PROF {:<28} {:8.2} ms  x{}", e.0, e.1 * 1e3, e.2);
    }
    t.clear();
}
