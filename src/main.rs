//! `rigidlab`: the command line (and, with the `app` feature, the sandbox window). In a web page
//! (wasm32 with the `app` feature) the same binary is the sandbox drawn into the page's canvas.

#[cfg(not(all(target_arch = "wasm32", feature = "app")))]
fn main() -> std::process::ExitCode {
    rigidlab::cli::main()
}

#[cfg(all(target_arch = "wasm32", feature = "app"))]
fn main() {
    rigidlab::app::web::start()
}
