//! The `tribo` command: parses arguments, runs, prints the error chain, sets the exit code.

// mimalloc keeps and reuses the memory it maps: glibc's malloc returns large blocks to the
// system and page-faults them in again (SSNP154 B: 24 000 page faults per run, 330 here).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() {
    match tribo::cli::main() {
        Ok(code) => std::process::exit(code),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    }
}
