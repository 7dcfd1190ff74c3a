# cmake -DLIBRARY=<target> -DLINKS=<its static link closure, a,b,c> -DFORBIDDEN=<x,y> -P check_links.cmake
# Fails, naming them, when a library links (directly or through others) a
# target it must stay off; also when the closure does not even hold the
# library itself (the list was not computed).
cmake_minimum_required(VERSION 3.25)
string(REPLACE "," ";" links "${LINKS}")
string(REPLACE "," ";" forbidden "${FORBIDDEN}")
if(NOT LIBRARY IN_LIST links)
  message(FATAL_ERROR "${LIBRARY}: its link closure is missing or empty ('${LINKS}')")
endif()
set(bad "")
foreach(t IN LISTS forbidden)
  if(t IN_LIST links)
    list(APPEND bad ${t})
  endif()
endforeach()
if(bad)
  message(FATAL_ERROR "${LIBRARY} links ${bad} (its closure: ${links}), which it must stay off")
endif()
message(STATUS "${LIBRARY} links ${links}: none of ${forbidden}")
