#include <lagfsi/app.hpp>

int main(int argc, char** argv) { return lagfsi::app_main(argc, argv); }
