//! The `billiard-contact` command: the library's command line (`src/cli/`).

fn main() -> std::process::ExitCode {
    billiard_contact::cli::main()
}
