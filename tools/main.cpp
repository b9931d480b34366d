// sm2: the command line of sm2emu.
#include <iostream>

#include "commands.h"

int main(int argc, char** argv) {
    CLI::App app{"sm2emu: a software Shader Model 2.0 GPU (vs_2_0 / ps_2_0)", "sm2"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "sm2emu 0.1.0");
    int status = sm2::tools::kOk;
    sm2::tools::add_shader_commands(app, status);
    sm2::tools::add_run_command(app, status);
    sm2::tools::add_stream_commands(app, status);
    sm2::tools::add_replay_commands(app, status);
    sm2::tools::add_diff_command(app, status);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return sm2::tools::kBadUsage;
    }
    return status;
}
