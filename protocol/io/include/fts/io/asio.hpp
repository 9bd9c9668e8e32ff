// The one way to include Boost.Asio, for fts-server, fts-client and fts-bot alike:
// Boost 1.74's awaitable.hpp uses std::exchange without including <utility> (fails with
// g++ 12 in C++20), and we use no coroutines.
#pragma once

#include <utility>
#define BOOST_ASIO_DISABLE_CO_AWAIT 1
#include <boost/asio.hpp>
