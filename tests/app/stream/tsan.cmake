# The stream under ThreadSanitizer (issue 21; the TSan stage of scripts/test.sh, configured with
# -DRCSIM_TSAN=ON into build-tsan/). Every library is instrumented, through rcsim_warnings, which
# each one links; the stream's tests that run in-process go into an executable of their own,
# rcsim_stream_tests, so that the stage builds only the layers the stream uses (common, io, world,
# sim, replay_import, stream). The tests that spawn processes live elsewhere
# (tests/app/cli/listen_command_test.cpp: rcsim, which would need every layer instrumented;
# tests/end_to_end/wireshark_dissector_test.cpp: tshark): those processes run the same Streamer
# and Listener the in-process tests run on their threads.
if(RCSIM_SANITIZE OR RCSIM_FUZZ)
  message(FATAL_ERROR "RCSIM_TSAN cannot be combined with RCSIM_SANITIZE or RCSIM_FUZZ")
endif()
# -Wno-tsan: GCC warns that TSan does not model the atomic_thread_fence in Boost.Asio's
# std_fenced_block; the handlers it guards are handed over under the scheduler's mutex, which it does.
target_compile_options(rcsim_warnings INTERFACE -fsanitize=thread -fno-omit-frame-pointer -Wno-tsan)
target_link_options(rcsim_warnings INTERFACE -fsanitize=thread)

file(GLOB RCSIM_STREAM_TSAN_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/*_test.cpp)
rcsim_unity(RCSIM_STREAM_TSAN_SOURCES rcsim_stream_tests ${RCSIM_STREAM_TSAN_SOURCES})
add_executable(rcsim_stream_tests ${RCSIM_STREAM_TSAN_SOURCES})
target_link_libraries(rcsim_stream_tests PRIVATE rcsim_stream rcsim_test_paths GTest::gtest GTest::gtest_main rcsim_warnings)
target_include_directories(rcsim_stream_tests PRIVATE ${CMAKE_SOURCE_DIR}/tests)
gtest_discover_tests(rcsim_stream_tests TEST_PREFIX "tsan." PROPERTIES LABELS tsan DISCOVERY_TIMEOUT 60)
