# Writes OUT: one ctest test per GoogleTest suite of TEST_EXE (run with
# --gtest_filter=SUITE.*), so that a suite's tests share one process. Suites listed in
# SPLIT get one ctest test per test instead (the extreme suite's shards: each is minutes,
# and ctest -j spreads them). COST (the suite's test count; SPLIT tests 1000) makes
# ctest -j start the long ones first. Run after every build of TEST_EXE (CMakeLists.txt).
# Each process writes its GoogleTest XML report to XML/<suite>.xml, from which
# scripts/test-report.sh counts the tests one by one. Suites instantiated as Nightly/... are
# left out: the nightly job runs them (scripts/nightly.sh), too heavy for the test command.
# Usage: cmake -DTEST_EXE=... -DOUT=... -DWORKDIR=... -DSKIPS=dir -DXML=dir -P TestSuites.cmake
cmake_minimum_required(VERSION 3.25)
set(SPLIT "Shard/ExtremeSuite")
execute_process(COMMAND ${TEST_EXE} --gtest_list_tests OUTPUT_VARIABLE listing
                RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${TEST_EXE} --gtest_list_tests failed (${status})")
endif()
string(REPLACE ";" "\\;" listing "${listing}")
string(REPLACE "\n" ";" lines "${listing}")

set(env "SB_VALIDATION=1;SB_SKIP_LOG=${SKIPS}")
set(body "")
set(suite "")
set(count 0)
macro(flush_suite)
  if(NOT suite STREQUAL "" AND NOT suite IN_LIST SPLIT AND NOT suite MATCHES "^Nightly/")
    string(REPLACE "/" "_" file "${suite}")
    string(APPEND body "add_test([=[${suite}]=] [=[${TEST_EXE}]=] [=[--gtest_filter=${suite}.*]=] "
      "[=[--gtest_output=xml:${XML}/${file}.xml]=])\n"
      "set_tests_properties([=[${suite}]=] PROPERTIES WORKING_DIRECTORY [=[${WORKDIR}]=] "
      "ENVIRONMENT [==[${env}]==] COST ${count})\n")
  endif()
endmacro()
foreach(line IN LISTS lines)
  if(line MATCHES "^([^ #][^ ]*)\\.$")
    set(next "${CMAKE_MATCH_1}")  # flush_suite's own MATCHES resets CMAKE_MATCH_1
    flush_suite()
    set(suite "${next}")
    set(count 0)
  elseif(line MATCHES "^  ([^ ]+)")
    math(EXPR count "${count} + 1")
    if(suite IN_LIST SPLIT)
      set(name "${suite}.${CMAKE_MATCH_1}")
      string(REPLACE "/" "_" file "${name}")
      string(APPEND body "add_test([=[${name}]=] [=[${TEST_EXE}]=] [=[--gtest_filter=${name}]=] "
        "[=[--gtest_output=xml:${XML}/${file}.xml]=])\n"
        "set_tests_properties([=[${name}]=] PROPERTIES WORKING_DIRECTORY [=[${WORKDIR}]=] "
        "ENVIRONMENT [==[${env}]==] COST 1000)\n")
    endif()
  endif()
endforeach()
flush_suite()
file(WRITE "${OUT}.new" "${body}")
file(RENAME "${OUT}.new" "${OUT}")
