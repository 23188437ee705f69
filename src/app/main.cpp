#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
  CLI::App app{"impactfe: finite elements for structural impact dynamics"};
  CLI11_PARSE(app, argc, argv);
  return 0;
}
