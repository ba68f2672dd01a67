// rooms.hpp - the world the houghloc-sim tests share.
#ifndef HLSIM_TEST_ROOMS_HPP
#define HLSIM_TEST_ROOMS_HPP

#include <string>

#include "world.hpp"

// A 6 m square room centred on the origin: every wall 3 m from it.
inline hlsim::World six_metre_room()
{
    hlsim::World w;
    std::string err;
    w.parse("polygon -3000 -3000 3000 -3000 3000 3000 -3000 3000\n", "room", &err);
    return w;
}

#endif
