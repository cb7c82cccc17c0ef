#include <lagfsi/app/app.hpp>

#include "git_version.hpp"  // LAGFSI_GIT_COMMIT, written at build time (cmake/git_version.cmake)

int main(int argc, char** argv) { return lagfsi::app_main(argc, argv, LAGFSI_GIT_COMMIT); }
