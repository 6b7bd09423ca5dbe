//! The `tribo` command: parses arguments, runs, prints the error chain, sets the exit code.

/// Allocations past 90 % of the memory available at the start fail inside the process
/// (see `alloc_cap`), before the kernel's OOM killer ends it without a word.
#[global_allocator]
static ALLOCATOR: tribo::alloc_cap::Capped = tribo::alloc_cap::Capped;

fn main() {
    // A closed or full standard output (`| head`, `> /dev/full`) makes `println!` panic:
    // end quietly with a non-zero status instead, and only that; any other panic is a bug
    // and is reported as one.
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let msg = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if msg.starts_with("failed printing to stdout") {
            std::process::exit(3);
        }
        default_hook(info);
    }));
    tribo::cli::keep_freed_memory();
    if let Some((bytes, _)) = tribo::memory::available() {
        tribo::alloc_cap::cap_from_now(bytes / 10 * 9);
    }
    // before any thread starts (they inherit its signal mask)
    tribo::cli::run::signals::install();
    match tribo::cli::on_worker_thread(tribo::cli::main) {
        Ok(code) => std::process::exit(code),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    }
}
