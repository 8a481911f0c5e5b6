// The command line's main(), compiled into the WebAssembly module as the
// function deltamesh_cli_main: the page runs exactly the CLI (same switch
// parser, pipeline, writers, -V report and error messages), on files in
// Emscripten's in-memory file system. Its headers are included first so the
// rename touches only main.cpp's own definition.
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "../../apps/deltamesh/cli.hpp"

#define main deltamesh_cli_main
#include "../../apps/deltamesh/main.cpp"
#undef main
