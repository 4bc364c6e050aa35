fn main() -> std::process::ExitCode {
    accelbench::cli::main()
}
