# The viewer in a real browser: headless Chromium, no network, loads the shelf demo's page from
# disk at its first and last frame. Checks that the page reports it is ready, that no script error
# was recorded, that the image is not blank (luminance variance measured by the page on its own
# drawing buffer) and that both the image and the screenshot change between the two frames. Then
# a page of the gantry's tool pressed 0.04 into the seam of a slab of two touching boxes
# (gantry_tool.urdf, slab_scene.urdf): the pair's arrow and the body-depth arrow are both shown,
# the body arrow 0.04 long (the deepest pair is 0.035), and the panel has the "body depth" layer.
#   cmake -DTOOL=deepcheck -DCHROMIUM=chromium -DDATA=robots/data -DPATH_FILE=path.txt -DWORK=dir
#         -P browser_test.cmake
# Prints "skipped: ..." and succeeds when no browser was found (ctest reports it as skipped).
if(NOT CHROMIUM OR NOT EXISTS "${CHROMIUM}")
  message("skipped: no Chromium found (install Debian's chromium or chromium-headless-shell)")
  return()
endif()
# A blank page has variance 0; the demo's image is measured far above this.
set(min_variance 50)

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(page "${WORK}/demo.html")
execute_process(
  COMMAND "${TOOL}" view --robot "${DATA}/deepcheck_arm/urdf/deepcheck_arm.urdf"
          --srdf "${DATA}/deepcheck_arm/srdf/deepcheck_arm.srdf" --scene "${DATA}/scenes/shelf.urdf"
          --package-path "${DATA}" --path "${PATH_FILE}" --out "${page}"
  RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "deepcheck view failed (${status}): ${err}")
endif()

# Every request outside the page fails: no proxy reachable, no name resolves.
set(browser "${CHROMIUM}" --headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader
    --window-size=1200,800 --proxy-server=127.0.0.1:9 "--host-resolver-rules=MAP * ~NOTFOUND"
    --no-first-run --disable-extensions "--user-data-dir=${WORK}/profile")

# Loads `url` with the probe, fails unless the page reports ready without a script error, and
# sets `dom` (the page's DOM) and `root` (its <html> tag) in the caller; `what` names the page.
function(load_probed url what)
  execute_process(COMMAND ${browser} --dump-dom "${url}"
                  OUTPUT_VARIABLE dom ERROR_VARIABLE log RESULT_VARIABLE status TIMEOUT 180)
  string(REGEX MATCH "<html[^>]*>" root "${dom}")
  if(NOT status EQUAL 0 OR NOT root MATCHES "data-ready=\"1\"")
    message(FATAL_ERROR "${what}: the page did not report ready (status ${status}): ${root}\n${log}")
  endif()
  if(root MATCHES "data-error=\"([^\"]*)\"")
    message(FATAL_ERROR "${what}: script error: ${CMAKE_MATCH_1}")
  endif()
  set(dom "${dom}" PARENT_SCOPE)
  set(root "${root}" PARENT_SCOPE)
endfunction()

foreach(frame 0 end)
  load_probed("file://${page}#t=${frame},probe" "#t=${frame}")
  string(REGEX MATCH "data-pixel-variance=\"([0-9.]+)\"" _ "${root}")
  set(variance "${CMAKE_MATCH_1}")
  string(REGEX MATCH "data-pixel-hash=\"([0-9a-f]+)\"" _ "${root}")
  set(hash_${frame} "${CMAKE_MATCH_1}")
  if(variance STREQUAL "" OR variance LESS min_variance)
    message(FATAL_ERROR "#t=${frame}: the image looks blank (luminance variance '${variance}' < ${min_variance})")
  endif()
  message("#t=${frame}: ready, no script error, luminance variance ${variance}, image hash ${hash_${frame}}")

  set(png "${WORK}/frame_${frame}.png")
  execute_process(COMMAND ${browser} "--screenshot=${png}" "file://${page}#t=${frame}"
                  OUTPUT_QUIET ERROR_VARIABLE log RESULT_VARIABLE status TIMEOUT 180)
  if(NOT status EQUAL 0 OR NOT EXISTS "${png}")
    message(FATAL_ERROR "#t=${frame}: no screenshot (status ${status})\n${log}")
  endif()
  file(SHA256 "${png}" png_${frame})
endforeach()

if(hash_0 STREQUAL hash_end)
  message(FATAL_ERROR "the image is the same at the first and the last frame (hash ${hash_0})")
endif()
if(png_0 STREQUAL png_end)
  message(FATAL_ERROR "the screenshots of the first and the last frame are identical")
endif()
message("first and last frame differ (images and screenshots)")

# The body-depth arrow.
set(slab_page "${WORK}/slab.html")
execute_process(
  COMMAND "${TOOL}" view --robot "${CMAKE_CURRENT_LIST_DIR}/gantry_tool.urdf"
          --scene "${CMAKE_CURRENT_LIST_DIR}/slab_scene.urdf" --config 0.005 0 0.01 0 0 --out "${slab_page}"
  RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "deepcheck view (slab) failed (${status}): ${err}")
endif()
load_probed("file://${slab_page}#t=0,probe" "slab")
if(NOT root MATCHES "data-arrows=\"contact,body depth\"")
  message(FATAL_ERROR "slab: the pair's and the body-depth arrows are not both shown: ${root}")
endif()
if(NOT root MATCHES "data-body-depth=\"0\\.0400000\"")
  message(FATAL_ERROR "slab: the body-depth arrow is not 0.04 long: ${root}")
endif()
if(NOT dom MATCHES "<label title=\"body depth\">")
  message(FATAL_ERROR "slab: the panel has no 'body depth' layer")
endif()
message("slab: the pair's arrow and the body-depth arrow (0.04) shown, 'body depth' layer in the panel")
