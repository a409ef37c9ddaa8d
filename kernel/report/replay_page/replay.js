/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The replay page's behaviour: it reads the run's data from the JSON element #replay-data,
 * draws the scene top-down (north up) at the cursor's time, and keeps the panels, plots and log
 * in step with the cursor. Every text from the data goes into the page as textContent or as
 * canvas text, never as markup. Nothing is fetched: the page is one file.
 *
 * Hooks for tests (tests/report/replay_page_browser_test.cc reads them):
 *   canvas#scene  data-origin-x, data-origin-y: the CSS-pixel position of world (0, 0) inside the
 *                 canvas; data-px-per-m: CSS pixels per metre (x grows east, y grows downward on
 *                 screen, so north is up); data-page-left, data-page-top: the canvas's top-left
 *                 corner on the page, in CSS pixels.
 *   body          data-cursor: the cursor's time in seconds; data-ready="1" once drawn.
 *   The first robot that is not a ghost is filled in #e6007e, fully opaque, with only a thin
 *   heading line over it; nothing else on the page is drawn in that colour.
 * The address's fragment sets the cursor and the speed at load: #t=12.5&speed=4.
 */
(function () {
  'use strict';

  var FIRST_ROBOT_COLOUR = '#e6007e';
  var FIRST_ROBOT_TRAIL = 'rgba(230, 0, 126, 0.4)';
  var OTHER_ROBOT_COLOURS = ['#1e6fd9', '#2e7d32', '#6a1b9a', '#00838f', '#5d4037'];
  var GHOST_COLOUR = 'rgba(255, 143, 0, 0.5)';
  var GHOST_TRAIL = 'rgba(255, 143, 0, 0.4)';
  var SCENERY_COLOURS = {wall: '#8d6e63', post: '#3e2723', obstacle: '#546e7a'};
  var KNOWN_WALL_COLOUR = 'rgba(21, 101, 192, 0.85)';
  var VISITED_COLOUR = 'rgba(21, 101, 192, 0.10)';
  var PLANNED_PATH_COLOUR = '#2e7d32';
  var SPEEDS = [0.1, 0.25, 0.5, 1, 2, 4, 8, 16];
  var LOG_LINES = 12;
  var LEVEL_NAMES = {1: 'debug', 2: 'info', 3: 'warning', 4: 'error'};
  // wall bits of a beliefs entry: N 1, E 2, S 4, W 8, each as the edge it lies on
  var WALL_EDGES = [[1, 0, 1, 1, 1], [2, 1, 0, 1, 1], [4, 0, 0, 1, 0], [8, 0, 0, 0, 1]];

  function byId(id) { return document.getElementById(id); }

  function element(tag, className, text) {
    var node = document.createElement(tag);
    if (className) node.className = className;
    if (text !== undefined) node.textContent = text;
    return node;
  }

  function array(value) { return Array.isArray(value) ? value : []; }
  function isNumber(value) { return typeof value === 'number' && isFinite(value); }
  function number(value, fallback) { return isNumber(value) ? value : fallback; }
  function text(value) { return value === null || value === undefined ? '' : String(value); }

  function seconds(t) { return t.toFixed(3); }

  // a value as a panel shows it: whole numbers whole, others to six significant digits
  function shown(value) {
    if (!isNumber(value)) return text(value);
    if (Number.isInteger(value)) return String(value);
    return String(Number(value.toPrecision(6)));
  }

  // index of the last of the increasing `times` that is <= t, or -1
  function lastAtOrBefore(times, t) {
    var low = 0, high = times.length;
    while (low < high) {
      var middle = (low + high) >> 1;
      if (times[middle] <= t) low = middle + 1; else high = middle;
    }
    return low - 1;
  }

  // index of the last of the increasing `times` that is < t, or -1
  function lastBefore(times, t) {
    var low = 0, high = times.length;
    while (low < high) {
      var middle = (low + high) >> 1;
      if (times[middle] < t) low = middle + 1; else high = middle;
    }
    return low - 1;
  }

  // entries with a time, in time order (the sort is stable, so equal times keep their order)
  function byTime(list) {
    return array(list).filter(function (entry) {
      return entry !== null && typeof entry === 'object' && isNumber(entry.t);
    }).sort(function (a, b) { return a.t - b.t; });
  }

  function times(entries) { return entries.map(function (entry) { return entry.t; }); }

  function shortAngle(angle) { return Math.atan2(Math.sin(angle), Math.cos(angle)); }

  // ---- the data --------------------------------------------------------------------------------

  var data = null;
  try {
    data = JSON.parse(byId('replay-data').textContent);
  } catch (error) {
    data = null;
  }
  if (data === null || typeof data !== 'object') {
    byId('title').textContent = 'The replay\'s data cannot be read.';
    return;
  }

  var scenery = array(data.scenery).filter(function (box) {
    return box && isNumber(box.x) && isNumber(box.y) && isNumber(box.size_x) &&
        isNumber(box.size_y);
  });
  var cellM = isNumber(data.cell_m) && data.cell_m > 0 ? data.cell_m : null;

  var firstRobot = null;
  var otherColours = 0;
  var robots = array(data.robots).filter(function (robot) {
    return robot && typeof robot === 'object';
  }).map(function (robot) {
    var t = array(robot.t), x = array(robot.x), y = array(robot.y), yaw = array(robot.yaw);
    var count = Math.min(t.length, x.length, y.length, yaw.length);
    var made = {
      name: text(robot.name), ghost: robot.ghost === true, source: text(robot.source),
      length: number(robot.length_m, 0.1), width: number(robot.width_m, 0.08),
      t: t.slice(0, count), x: x.slice(0, count), y: y.slice(0, count), yaw: yaw.slice(0, count)
    };
    if (made.ghost) {
      made.fill = GHOST_COLOUR;
      made.trail = GHOST_TRAIL;
    } else if (firstRobot === null) {
      firstRobot = made;
      made.fill = FIRST_ROBOT_COLOUR;
      made.trail = FIRST_ROBOT_TRAIL;
    } else {
      made.fill = OTHER_ROBOT_COLOURS[otherColours++ % OTHER_ROBOT_COLOURS.length];
      made.trail = made.fill;
    }
    return made;
  });

  var signals = data.signals && typeof data.signals === 'object' ? data.signals : {};
  var signalTimes = array(signals.t);
  var series = array(signals.series).filter(function (one) {
    return one && typeof one === 'object';
  });

  var events = byTime(data.events);
  var eventTimes = times(events);
  var log = byTime(data.log);
  var logTimes = times(log);
  var beliefs = byTime(data.beliefs);
  var beliefTimes = times(beliefs);
  var hud = byTime(data.hud);
  var hudTimes = times(hud);
  var values = byTime(data.values);
  var valueTimes = times(values);
  var divergence = data.divergence && typeof data.divergence === 'object' &&
      isNumber(data.divergence.t) ? data.divergence : null;

  // the run's length; from the samples when the data does not say
  var endS = number(data.end_s, 0);
  if (!(endS > 0)) {
    robots.forEach(function (robot) {
      if (robot.t.length > 0) endS = Math.max(endS, robot.t[robot.t.length - 1]);
    });
    if (signalTimes.length > 0) {
      endS = Math.max(endS, number(signalTimes[signalTimes.length - 1], 0));
    }
    endS = Math.max(endS, 0);
  }

  // stepping goes sample by sample of robot 0 (of the signals when there is no robot)
  var stepTimes = robots.length > 0 && robots[0].t.length > 0 ? robots[0].t : signalTimes;

  // ---- the scene's extent and mapping -----------------------------------------------------------

  function boxCorners(box) {
    var c = Math.cos(number(box.yaw, 0)), s = Math.sin(number(box.yaw, 0));
    var hx = box.size_x / 2, hy = box.size_y / 2;
    return [[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]].map(function (p) {
      return [box.x + c * p[0] - s * p[1], box.y + s * p[0] + c * p[1]];
    });
  }

  // the scenery's extent, and the robots' paths' (a robot may leave the maze), with a margin
  var extent = (function () {
    var e = {minX: Infinity, minY: Infinity, maxX: -Infinity, maxY: -Infinity};
    function add(x, y, reach) {
      if (!isNumber(x) || !isNumber(y)) return;
      e.minX = Math.min(e.minX, x - reach);
      e.maxX = Math.max(e.maxX, x + reach);
      e.minY = Math.min(e.minY, y - reach);
      e.maxY = Math.max(e.maxY, y + reach);
    }
    scenery.forEach(function (box) {
      boxCorners(box).forEach(function (p) { add(p[0], p[1], 0); });
    });
    robots.forEach(function (robot) {
      var reach = Math.hypot(robot.length, robot.width) / 2;
      for (var i = 0; i < robot.t.length; i++) add(robot.x[i], robot.y[i], reach);
    });
    if (!(e.maxX > e.minX)) { e.minX = -0.5; e.maxX = 0.5; }
    if (!(e.maxY > e.minY)) { e.minY = -0.5; e.maxY = 0.5; }
    var margin = Math.max(0.03, 0.04 * Math.max(e.maxX - e.minX, e.maxY - e.minY));
    e.minX -= margin; e.maxX += margin; e.minY -= margin; e.maxY += margin;
    return e;
  })();

  var scene = byId('scene');
  var view = {scale: 1, originX: 0, originY: 0, width: 1, height: 1, ratio: 1};

  function screenX(x) { return view.originX + x * view.scale; }
  function screenY(y) { return view.originY - y * view.scale; }

  function layoutScene() {
    var box = byId('scene-box');
    var spanX = extent.maxX - extent.minX, spanY = extent.maxY - extent.minY;
    var width = Math.max(160, Math.floor(box.clientWidth));
    // its height follows its width alone, not the window's height (the timeline above it stays
    // in sight when the page scrolls), so that the drawing does not change with a window's bars
    var maxHeight = Math.max(300, Math.min(820, width));
    var scale = Math.min(width / spanX, maxHeight / spanY);
    var height = Math.ceil(spanY * scale);
    view.scale = scale;
    view.width = width;
    view.height = height;
    view.ratio = window.devicePixelRatio || 1;
    view.originX = (width - spanX * scale) / 2 - extent.minX * scale;
    view.originY = (height - spanY * scale) / 2 + extent.maxY * scale;
    scene.style.width = width + 'px';
    scene.style.height = height + 'px';
    scene.width = Math.round(width * view.ratio);
    scene.height = Math.round(height * view.ratio);
    scene.dataset.originX = String(view.originX);
    scene.dataset.originY = String(view.originY);
    scene.dataset.pxPerM = String(scale);
  }

  // ---- drawing the scene ------------------------------------------------------------------------

  function fillBox(ctx, x, y, yaw, sizeX, sizeY) {
    ctx.save();
    ctx.translate(screenX(x), screenY(y));
    ctx.rotate(-yaw);  // counter-clockwise in the world is counter-clockwise on screen
    ctx.fillRect(-sizeX * view.scale / 2, -sizeY * view.scale / 2, sizeX * view.scale,
                 sizeY * view.scale);
    ctx.restore();
  }

  function cellCentre(x, y) { return [(x + 0.5) * cellM, (y + 0.5) * cellM]; }

  function isCell(entry, length) {
    return Array.isArray(entry) && entry.length >= length && isNumber(entry[0]) &&
        isNumber(entry[1]);
  }

  function drawBeliefsUnderScenery(ctx, belief) {
    ctx.save();
    array(belief.colours).forEach(function (entry) {
      if (!isCell(entry, 3) || !/^#[0-9a-fA-F]{6}$/.test(text(entry[2]))) return;
      // translucent, so that no floor tile can take a robot's colour
      ctx.globalAlpha = 0.45;
      ctx.fillStyle = entry[2];
      ctx.fillRect(screenX(entry[0] * cellM), screenY((entry[1] + 1) * cellM),
                   cellM * view.scale, cellM * view.scale);
    });
    ctx.globalAlpha = 1;
    ctx.fillStyle = VISITED_COLOUR;
    array(belief.visited).forEach(function (entry) {
      if (!isCell(entry, 2)) return;
      ctx.fillRect(screenX(entry[0] * cellM), screenY((entry[1] + 1) * cellM),
                   cellM * view.scale, cellM * view.scale);
    });
    ctx.restore();
  }

  function drawBeliefsOverScenery(ctx, belief) {
    ctx.save();
    ctx.strokeStyle = KNOWN_WALL_COLOUR;
    ctx.lineWidth = Math.max(3, 0.008 * view.scale);
    ctx.lineCap = 'butt';
    ctx.beginPath();
    array(belief.walls).forEach(function (entry) {
      if (!isCell(entry, 4) || !isNumber(entry[2]) || !isNumber(entry[3])) return;
      var shownBits = entry[2] & entry[3];
      WALL_EDGES.forEach(function (edge) {
        if ((shownBits & edge[0]) === 0) return;
        ctx.moveTo(screenX((entry[0] + edge[1]) * cellM), screenY((entry[1] + edge[2]) * cellM));
        ctx.lineTo(screenX((entry[0] + edge[3]) * cellM), screenY((entry[1] + edge[4]) * cellM));
      });
    });
    ctx.stroke();

    var path = array(belief.path).filter(function (entry) { return isCell(entry, 2); });
    if (path.length > 1) {
      ctx.strokeStyle = PLANNED_PATH_COLOUR;
      ctx.lineWidth = 2;
      ctx.setLineDash([6, 4]);
      ctx.lineJoin = 'round';
      ctx.beginPath();
      path.forEach(function (entry, i) {
        var c = cellCentre(entry[0], entry[1]);
        if (i === 0) ctx.moveTo(screenX(c[0]), screenY(c[1]));
        else ctx.lineTo(screenX(c[0]), screenY(c[1]));
      });
      ctx.stroke();
      ctx.setLineDash([]);
    }

    var fontSize = Math.max(9, Math.min(13, cellM * view.scale / 4));
    ctx.font = fontSize + 'px system-ui, sans-serif';
    ctx.textAlign = 'center';
    ctx.textBaseline = 'middle';
    ctx.fillStyle = '#263238';
    array(belief.texts).forEach(function (entry) {
      if (!isCell(entry, 3)) return;
      var c = cellCentre(entry[0], entry[1]);
      ctx.fillText(text(entry[2]).slice(0, 12), screenX(c[0]), screenY(c[1]), cellM * view.scale);
    });
    ctx.restore();
  }

  // a robot's pose at time t: linear between its samples, its heading the short way round
  function poseAt(robot, t) {
    var count = robot.t.length;
    if (count === 0) return null;
    var i = lastAtOrBefore(robot.t, t);
    if (i < 0) return {x: robot.x[0], y: robot.y[0], yaw: robot.yaw[0], index: -1};
    if (i >= count - 1) {
      return {x: robot.x[count - 1], y: robot.y[count - 1], yaw: robot.yaw[count - 1], index: i};
    }
    var t0 = robot.t[i], t1 = robot.t[i + 1];
    var f = t1 > t0 ? (t - t0) / (t1 - t0) : 0;
    return {
      x: robot.x[i] + f * (robot.x[i + 1] - robot.x[i]),
      y: robot.y[i] + f * (robot.y[i + 1] - robot.y[i]),
      yaw: robot.yaw[i] + f * shortAngle(robot.yaw[i + 1] - robot.yaw[i]),
      index: i
    };
  }

  function drawTrail(ctx, robot, pose) {
    if (pose.index < 0) return;
    ctx.save();
    ctx.strokeStyle = robot.trail;
    ctx.globalAlpha = robot.trail === robot.fill ? 0.5 : 1;
    ctx.lineWidth = 2;
    ctx.lineJoin = 'round';
    ctx.beginPath();
    ctx.moveTo(screenX(robot.x[0]), screenY(robot.y[0]));
    for (var i = 1; i <= pose.index; i++) ctx.lineTo(screenX(robot.x[i]), screenY(robot.y[i]));
    ctx.lineTo(screenX(pose.x), screenY(pose.y));
    ctx.stroke();
    ctx.restore();
  }

  function drawRobot(ctx, robot, pose) {
    ctx.save();
    ctx.translate(screenX(pose.x), screenY(pose.y));
    ctx.rotate(-pose.yaw);
    var length = robot.length * view.scale, width = robot.width * view.scale;
    ctx.fillStyle = robot.fill;
    ctx.fillRect(-length / 2, -width / 2, length, width);
    if (robot.ghost) {
      ctx.strokeStyle = 'rgba(230, 81, 0, 0.8)';
      ctx.lineWidth = 1;
      ctx.setLineDash([3, 3]);
      ctx.strokeRect(-length / 2, -width / 2, length, width);
      ctx.setLineDash([]);
    }
    // the heading: a thin line from the centre to the front, small beside the body
    ctx.strokeStyle = '#ffffff';
    ctx.lineWidth = Math.max(1, Math.min(3, width * 0.1));
    ctx.beginPath();
    ctx.moveTo(0, 0);
    ctx.lineTo(length / 2, 0);
    ctx.stroke();
    ctx.restore();
  }

  function drawScene() {
    var ctx = scene.getContext('2d');
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, scene.width, scene.height);
    ctx.setTransform(view.ratio, 0, 0, view.ratio, 0, 0);  // CSS pixels from here on
    ctx.fillStyle = '#f5f2ea';
    ctx.fillRect(0, 0, view.width, view.height);

    var belief = null;
    if (cellM !== null) {
      var b = lastAtOrBefore(beliefTimes, cursor);
      if (b >= 0) belief = beliefs[b];
    }
    if (belief) drawBeliefsUnderScenery(ctx, belief);
    scenery.forEach(function (box) {
      ctx.fillStyle = SCENERY_COLOURS[box.kind] || SCENERY_COLOURS.obstacle;
      fillBox(ctx, box.x, box.y, number(box.yaw, 0), box.size_x, box.size_y);
    });
    if (belief) drawBeliefsOverScenery(ctx, belief);

    var poses = robots.map(function (robot) { return poseAt(robot, cursor); });
    robots.forEach(function (robot, i) { if (poses[i]) drawTrail(ctx, robot, poses[i]); });
    // ghosts under the others, the first robot on top of all
    var order = robots.map(function (robot, i) { return i; }).sort(function (a, b) {
      function rank(i) { return robots[i].ghost ? 0 : robots[i] === firstRobot ? 2 : 1; }
      return rank(a) - rank(b) || a - b;
    });
    order.forEach(function (i) { if (poses[i]) drawRobot(ctx, robots[i], poses[i]); });

    var rect = scene.getBoundingClientRect();
    scene.dataset.pageLeft = String(rect.left + window.scrollX + scene.clientLeft);
    scene.dataset.pageTop = String(rect.top + window.scrollY + scene.clientTop);
  }

  // ---- the panels -------------------------------------------------------------------------------

  function buildStatic() {
    var title = text(data.title);
    byId('title').textContent = title === '' ? 'Replay' : title;
    document.title = title === '' ? 'Replay' : 'Replay: ' + title;

    var legend = byId('legend');
    robots.forEach(function (robot) {
      var item = element('li');
      var swatch = element('span', 'swatch' + (robot.ghost ? ' ghost' : ''));
      // the first robot's swatch is lighter than its body: its colour stays the body's alone
      swatch.style.background = robot === firstRobot ? FIRST_ROBOT_TRAIL : robot.fill;
      item.appendChild(swatch);
      item.appendChild(element('span', 'robot-name', robot.name));
      var about = [];
      if (robot.ghost) about.push('ghost');
      if (robot.source !== '') about.push(robot.source);
      if (about.length > 0) {
        item.appendChild(element('span', 'robot-about', ' (' + about.join(', ') + ')'));
      }
      legend.appendChild(item);
    });

    if (divergence !== null) {
      var line = byId('divergence');
      line.textContent = 'Divergence at ' + seconds(divergence.t) + ' s' +
          (isNumber(divergence.distance_m) ?
              ', ' + shown(divergence.distance_m) + ' m apart' : '') +
          (text(divergence.text) !== '' ? ': ' + text(divergence.text) : '');
      line.hidden = false;
    }

    var speedSelect = byId('speed');
    SPEEDS.forEach(function (value) {
      var option = element('option', '', value + 'x');
      option.value = String(value);
      speedSelect.appendChild(option);
    });

    var range = byId('cursor-range');
    range.max = String(endS);

    // the events and the divergence as ticks over the timeline
    var marks = byId('timeline-marks');
    function mark(t, className, title) {
      var tick = element('span', className);
      tick.style.left = (endS > 0 ? Math.min(100, Math.max(0, 100 * t / endS)) : 0) + '%';
      tick.title = title;
      marks.appendChild(tick);
    }
    events.forEach(function (event) {
      mark(event.t, 'event-mark', seconds(event.t) + ' s ' + text(event.kind));
    });
    if (divergence !== null) mark(divergence.t, 'divergence-mark', byId('divergence').textContent);

    var list = byId('events');
    events.forEach(function (event) {
      var item = element('li');
      var button = element('button', 'event');
      button.type = 'button';
      button.appendChild(element('span', 'time', seconds(event.t)));
      button.appendChild(element('span', 'kind', text(event.kind)));
      if (text(event.robot) !== '') button.appendChild(element('span', 'robot', text(event.robot)));
      button.appendChild(element('span', 'text', text(event.text)));
      button.addEventListener('click', function () {
        setPlaying(false);
        setCursor(event.t);
      });
      item.appendChild(button);
      list.appendChild(item);
    });
    if (events.length === 0) list.appendChild(element('li', 'empty', 'No events.'));
    byId('previous-event').disabled = events.length === 0;
    byId('next-event').disabled = events.length === 0;

    buildPlots();
  }

  var plots = [];

  function buildPlots() {
    var box = byId('plots');
    series.forEach(function (one) {
      var figure = element('figure', 'plot');
      figure.appendChild(element('figcaption', '', text(one.name)));
      var frame = element('div', 'plot-frame');
      var canvas = element('canvas', 'plot-canvas');
      var cursorLine = element('div', 'plot-cursor');
      var points = array(one.values);
      var count = Math.min(points.length, signalTimes.length);
      var low = Infinity, high = -Infinity;
      for (var i = 0; i < count; i++) {
        if (!isNumber(points[i])) continue;
        low = Math.min(low, points[i]);
        high = Math.max(high, points[i]);
      }
      var maxLabel = element('span', 'plot-max', isFinite(high) ? shown(high) : 'no values');
      var minLabel = element('span', 'plot-min', isFinite(low) ? shown(low) : '');
      frame.appendChild(canvas);
      frame.appendChild(cursorLine);
      frame.appendChild(maxLabel);
      frame.appendChild(minLabel);
      figure.appendChild(frame);
      box.appendChild(figure);
      plots.push({
        canvas: canvas, cursor: cursorLine, values: points, count: count, low: low, high: high
      });
    });
    if (series.length === 0) box.appendChild(element('p', 'empty', 'No signals were recorded.'));
  }

  function drawPlot(plot) {
    var ratio = window.devicePixelRatio || 1;
    var width = Math.max(50, Math.floor(plot.canvas.parentNode.clientWidth));
    var height = 90;
    plot.canvas.style.width = width + 'px';
    plot.canvas.style.height = height + 'px';
    plot.canvas.width = Math.round(width * ratio);
    plot.canvas.height = Math.round(height * ratio);
    var ctx = plot.canvas.getContext('2d');
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    ctx.fillStyle = '#fafafa';
    ctx.fillRect(0, 0, width, height);
    if (!isFinite(plot.low)) return;
    var low = plot.low, high = plot.high;
    if (high === low) { low -= 1; high += 1; }
    var pad = 4;
    function x(t) { return endS > 0 ? width * t / endS : 0; }
    function y(v) { return pad + (height - 2 * pad) * (high - v) / (high - low); }
    ctx.strokeStyle = '#1e6fd9';
    ctx.lineWidth = 1.25;
    ctx.beginPath();
    var drawing = false;
    for (var i = 0; i < plot.count; i++) {
      var v = plot.values[i], t = signalTimes[i];
      // a null value is a gap in the line
      if (!isNumber(v) || !isNumber(t)) { drawing = false; continue; }
      if (drawing) ctx.lineTo(x(t), y(v)); else ctx.moveTo(x(t), y(v));
      drawing = true;
    }
    ctx.stroke();
  }

  function showHud() {
    var box = byId('hud');
    box.textContent = '';
    var i = lastAtOrBefore(hudTimes, cursor);
    if (i < 0) {
      box.appendChild(element('div', 'empty', 'Nothing yet.'));
      return;
    }
    array(hud[i].lines).forEach(function (line) {
      box.appendChild(element('div', 'hud-line', text(line)));
    });
  }

  function showValues() {
    var body = byId('values').tBodies[0];
    body.textContent = '';
    var i = lastAtOrBefore(valueTimes, cursor);
    var entry = i >= 0 && values[i].values && typeof values[i].values === 'object' ?
        values[i].values : {};
    Object.keys(entry).forEach(function (name) {
      var row = element('tr');
      row.appendChild(element('th', '', name));
      row.appendChild(element('td', 'num', shown(entry[name])));
      body.appendChild(row);
    });
  }

  function showLog() {
    var body = byId('log').tBodies[0];
    body.textContent = '';
    var last = lastAtOrBefore(logTimes, cursor);
    for (var i = Math.max(0, last - LOG_LINES + 1); i <= last; i++) {
      var line = log[i];
      var level = LEVEL_NAMES[line.level] ? line.level : 2;
      var row = element('tr', 'log-line level-' + level);
      row.appendChild(element('td', 'num', seconds(line.t)));
      row.appendChild(element('td', 'level', LEVEL_NAMES[level]));
      row.appendChild(element('td', 'name', text(line.name)));
      row.appendChild(element('td', 'message', text(line.message)));
      body.appendChild(row);
    }
  }

  function markCurrentEvent() {
    var current = lastAtOrBefore(eventTimes, cursor);
    var items = byId('events').children;
    for (var i = 0; i < events.length; i++) items[i].classList.toggle('current', i === current);
  }

  // ---- the cursor -------------------------------------------------------------------------------

  var cursor = 0;
  var speed = 1;
  var playing = false;
  var lastFrame = null;
  var drawnEntries = {hud: null, values: null, log: null, events: null};

  // the address follows the cursor, at most four times a second: browsers throttle replaceState
  var addressTimer = null, addressWritten = 0;
  function addressFragment() {
    return '#t=' + seconds(cursor) + (speed !== 1 ? '&speed=' + speed : '');
  }
  function writeAddress() {
    addressTimer = null;
    addressWritten = Date.now();
    if (location.hash === addressFragment()) return;
    try {
      history.replaceState(null, '', addressFragment());
    } catch (error) {
      // a browser may refuse it for a file; the page works without
    }
  }
  function updateAddress() {
    if (addressTimer !== null) return;
    addressTimer = setTimeout(writeAddress, Math.max(0, 250 - (Date.now() - addressWritten)));
  }

  function setCursor(t, quiet) {
    cursor = Math.min(endS, Math.max(0, isNumber(t) ? t : 0));
    byId('cursor-range').value = String(cursor);
    byId('time').textContent = seconds(cursor) + ' s';
    document.body.dataset.cursor = String(cursor);
    drawScene();
    // the panels change only when their entry does
    var at = {
      hud: lastAtOrBefore(hudTimes, cursor), values: lastAtOrBefore(valueTimes, cursor),
      log: lastAtOrBefore(logTimes, cursor), events: lastAtOrBefore(eventTimes, cursor)
    };
    if (at.hud !== drawnEntries.hud) showHud();
    if (at.values !== drawnEntries.values) showValues();
    if (at.log !== drawnEntries.log) showLog();
    if (at.events !== drawnEntries.events) markCurrentEvent();
    drawnEntries = at;
    var left = (endS > 0 ? 100 * cursor / endS : 0) + '%';
    plots.forEach(function (plot) { plot.cursor.style.left = left; });
    if (!quiet) updateAddress();
  }

  function frame(now) {
    if (!playing) return;
    var elapsed = lastFrame === null ? 0 : Math.min(0.25, (now - lastFrame) / 1000);
    lastFrame = now;
    var next = cursor + elapsed * speed;
    if (next >= endS) {
      next = endS;
      setPlaying(false);
    }
    setCursor(next);
    if (playing) requestAnimationFrame(frame);
  }

  function setPlaying(on) {
    if (on === playing) return;
    playing = on && endS > 0;
    byId('play').textContent = playing ? 'Pause' : 'Play';
    byId('play').setAttribute('aria-pressed', playing ? 'true' : 'false');
    lastFrame = null;
    if (playing) {
      if (cursor >= endS) setCursor(0);
      requestAnimationFrame(frame);
    }
  }

  function step(direction) {
    setPlaying(false);
    if (stepTimes.length === 0) {
      setCursor(cursor + direction * 0.01);
      return;
    }
    var epsilon = 1e-9;
    if (direction > 0) {
      var next = lastAtOrBefore(stepTimes, cursor + epsilon) + 1;
      setCursor(next < stepTimes.length ? stepTimes[next] : endS);
    } else {
      var previous = lastBefore(stepTimes, cursor - epsilon);
      setCursor(previous >= 0 ? stepTimes[previous] : 0);
    }
  }

  function jumpToEvent(direction) {
    setPlaying(false);
    var epsilon = 1e-9;
    var i = direction > 0 ? lastAtOrBefore(eventTimes, cursor + epsilon) + 1 :
        lastBefore(eventTimes, cursor - epsilon);
    if (i >= 0 && i < events.length) setCursor(eventTimes[i]);
  }

  function setSpeed(value, quiet) {
    speed = value;
    // the chosen option carries the `selected` attribute too, so that the page's DOM tells it
    Array.prototype.forEach.call(byId('speed').options, function (option) {
      option.defaultSelected = option.value === String(value);
    });
    byId('speed').value = String(value);
    if (!quiet) updateAddress();
  }

  // #t=12.5&speed=4
  function readAddress() {
    var options = new URLSearchParams(location.hash.slice(1));
    var t = parseFloat(options.get('t'));
    var asked = parseFloat(options.get('speed'));
    return {t: isFinite(t) ? t : null, speed: SPEEDS.indexOf(asked) >= 0 ? asked : null};
  }

  function applyAddress() {
    var address = readAddress();
    if (address.speed !== null && address.speed !== speed) setSpeed(address.speed);
    if (address.t !== null && seconds(address.t) !== seconds(cursor)) setCursor(address.t, true);
  }

  // ---- controls ---------------------------------------------------------------------------------

  function connect() {
    byId('play').addEventListener('click', function () { setPlaying(!playing); });
    byId('step-back').addEventListener('click', function () { step(-1); });
    byId('step-forward').addEventListener('click', function () { step(1); });
    byId('previous-event').addEventListener('click', function () { jumpToEvent(-1); });
    byId('next-event').addEventListener('click', function () { jumpToEvent(1); });
    byId('speed').addEventListener('change', function () { setSpeed(Number(this.value)); });
    byId('cursor-range').addEventListener('input', function () { setCursor(Number(this.value)); });
    window.addEventListener('hashchange', applyAddress);
    window.addEventListener('resize', function () {
      layout();
      drawScene();
    });
    // anything that moved the canvas while the page loaded moves its page position too
    window.addEventListener('load', drawScene);
    document.addEventListener('keydown', function (event) {
      if (event.altKey || event.ctrlKey || event.metaKey) return;
      var target = event.target;
      var tag = target && target.tagName;
      if (tag === 'SELECT' || tag === 'TEXTAREA') return;
      if (tag === 'INPUT' && target.type !== 'range') return;
      if (event.key === ' ') {
        event.preventDefault();
        setPlaying(!playing);
      } else if (event.key === 'ArrowLeft') {
        event.preventDefault();
        step(-1);
      } else if (event.key === 'ArrowRight') {
        event.preventDefault();
        step(1);
      }
    });
    // a focused button would take the space as a click too
    document.addEventListener('keyup', function (event) {
      if (event.key === ' ' && event.target && event.target.tagName === 'BUTTON') {
        event.preventDefault();
      }
    });
  }

  function layout() {
    layoutScene();
    plots.forEach(drawPlot);
  }

  buildStatic();
  connect();
  layout();
  var address = readAddress();
  setSpeed(address.speed !== null ? address.speed : 1, true);
  setCursor(address.t !== null ? address.t : 0, true);
  document.body.dataset.ready = '1';
})();
