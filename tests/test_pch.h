// The headers most test files parse, precompiled once per build folder and shared by every test
// binary (tests/CMakeLists.txt): GoogleTest, gmock, nlohmann-json and the heavier standard ones.
// Only headers from outside luz, so that editing the renderer does not rebuild it.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>
