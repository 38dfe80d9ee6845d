fn main() -> std::process::ExitCode {
    rigidlab::cli::main()
}
