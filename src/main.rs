//! The `tribo` command: parses arguments, runs, prints the error chain, sets the exit code.

fn main() {
    match tribo::cli::main() {
        Ok(code) => std::process::exit(code),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    }
}
