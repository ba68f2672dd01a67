// test_support.hpp - includes cmocka from C++ (its header has no extern "C" of its own).
#ifndef HLSIM_TEST_SUPPORT_HPP
#define HLSIM_TEST_SUPPORT_HPP
#include <cstdarg>
#include <cstddef>
#include <cstdint>
#include <csetjmp>
#include <cmath>
#include <string>
#include <vector>
extern "C" {
#include <cmocka.h>
}

// cmocka's assert_float_equal works in float; the simulator's geometry needs doubles.
#define assert_near(a, b, eps)                                                          \
    do {                                                                                \
        double a_ = (a), b_ = (b);                                                      \
        if (!(std::fabs(a_ - b_) <= (eps))) {                                           \
            print_error("%s = %.12g, expected %.12g +- %g\n", #a, a_, b_, (double)(eps)); \
            fail();                                                                     \
        }                                                                               \
    } while (0)
#endif
