// doctest's main, in a translation unit of its own so that test files rebuild quickly.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
