// SPDX-License-Identifier: MIT
// Symbol visibility for libsc: everything not marked SC_API stays hidden.
#pragma once

#if defined(SC_STATIC_DEFINE)
#define SC_API
#elif defined(_WIN32)
#if defined(SC_BUILDING_LIBRARY)
#define SC_API __declspec(dllexport)
#else
#define SC_API __declspec(dllimport)
#endif
#else
#define SC_API __attribute__((visibility("default")))
#endif
