//! The `tribo` command: parses arguments, runs, prints the error chain, sets the exit code.

fn main() {
    tribo::cli::keep_freed_memory();
    match tribo::cli::on_worker_thread(tribo::cli::main) {
        Ok(code) => std::process::exit(code),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    }
}
