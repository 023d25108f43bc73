//! `lambert`: the command-line front end.

fn main() {
    println!("lambert");
}
