# platbench's step protocol (docs/protocol.md) for Godot 3's headless server: the real
# KinematicBody2D.move_and_slide (and move_and_slide_with_snap) of Godot 3.2, in "collision"
# mode. Run by platbench through controller.toml:
#   godot3-server --no-window --fixed-fps 60 -s client.gd
# Godot 3 cannot read its stdin, so the lines travel over TCP (transport = "tcp"): this script
# connects to 127.0.0.1 at the port in $PLATBENCH_PORT and quits when the connection closes.
#
# The level is built as a Godot game builds it: solid tiles as rectangle shapes of a
# StaticBody2D, one per tile (as a TileMap does) or merged into boxes; sloped tiles as convex
# polygons; one-way tiles with CollisionShape2D.one_way_collision; moving platforms as
# KinematicBody2D nodes with motion/sync_to_physics, moved to their path's position each step.
# Each step the character moves with the shared motion's desired velocity (y flipped, in pixels)
# and reports what Godot says: is_on_floor, is_on_wall, is_on_ceiling, get_floor_normal.
#
# Units: PIXELS_PER_TILE pixels per platbench tile, Godot's y down; platbench's y is up and a
# character's position is its feet, so the body's origin sits at the feet and its shape above.
extends SceneTree

const PROTOCOL = 1
# Pixels per tile: Godot's 2D demos draw 16 to 64 px tiles; at 32 px the platformer demo's
# 20 x 28 px player is about platbench's 0.8 x 0.9-tile character.
const PIXELS_PER_TILE = 32.0
# KinematicBody2D collision/safe_margin, Godot 3's default (px): the gap its recovery keeps.
const SAFE_MARGIN = 0.08
# move_and_slide's max_slides default in Godot 3 (class reference, KinematicBody2D), which the
# platformer demo passes too.
const MAX_SLIDES = 4
# The 2D platformer demo (godot-demo-projects 2d/platformer, src/Actors/Player.gd):
# FLOOR_DETECT_DISTANCE = 20 px of snap, floor_max_angle 0.9 rad, infinite_inertia false, and
# stop_on_slope off while on a moving platform (its PlatformDetector ray).
const DEMO_SNAP = 20.0
const DEMO_FLOOR_MAX_ANGLE = 0.9

const SOLID_LAYER = 1
const ONE_WAY_LAYER = 2

var peer = null
var buffer = PoolByteArray()
var config = {}
var characters = []
var platforms = []
var one_way_boxes = []
var dropping = []
var level_root = null
var origin_x = 0.0
var origin_y = 0.0
var engine_usec = 0
var frame_end = -1


func configs():
	var features = {"slopes": true, "one_way": true, "ladders": false, "moving_platforms": true}
	var margin = SAFE_MARGIN / PIXELS_PER_TILE
	var contact = {"gap": margin, "gap_tolerance": margin}
	return [
		{
			"label": "slide",
			"shape": "cuboid",
			"features": features,
			"contact": contact,
			"why": "move_and_slide(v, UP) with the class reference's defaults (no stop_on_slope, 4 slides, 45 deg), as the KinematicBody2D tutorial calls it; per-tile shapes, as a TileMap builds them",
		},
		{
			"label": "snap",
			"shape": "cuboid",
			"features": features,
			"contact": contact,
			"why": "move_and_slide_with_snap as the 2D platformer demo calls it: 20 px snap (none while jumping), 0.9 rad, stop_on_slope off on platforms; per-tile shapes",
		},
		{
			"label": "snap-merged",
			"shape": "cuboid",
			"features": features,
			"contact": contact,
			"why": "the demo's move_and_slide_with_snap on solid tiles merged into boxes (no seams between tiles)",
		},
	]


func _initialize():
	var port = OS.get_environment("PLATBENCH_PORT")
	if port == "":
		printerr("client.gd: no PLATBENCH_PORT: run me through platbench (controllers/godot3/controller.toml)")
		quit(2)
		return
	peer = StreamPeerTCP.new()
	if peer.connect_to_host("127.0.0.1", int(port)) != OK:
		printerr("client.gd: cannot connect to port ", port)
		quit(2)
		return
	while peer.get_status() == StreamPeerTCP.STATUS_CONNECTING:
		OS.delay_usec(100)
	peer.set_no_delay(true)


# The next line from platbench, or null when the connection closed.
func read_line():
	while true:
		for i in range(buffer.size()):
			if buffer[i] == 10:
				var line = buffer.subarray(0, i - 1).get_string_from_utf8() if i > 0 else ""
				if i + 1 < buffer.size():
					buffer = buffer.subarray(i + 1, buffer.size() - 1)
				else:
					buffer = PoolByteArray()
				return line
		if peer.get_status() != StreamPeerTCP.STATUS_CONNECTED:
			return null
		var got = peer.get_data(max(peer.get_available_bytes(), 1))
		if got[0] != OK:
			return null
		buffer.append_array(got[1])


func send(text):
	peer.put_data((text + "\n").to_utf8())


# JSON for a reply: Godot 3's to_json keeps 6 decimals, too few for a position in tiles, so
# floats are written with 9.
func json(value):
	match typeof(value):
		TYPE_REAL:
			return "%.9f" % value
		TYPE_INT:
			return str(value)
		TYPE_BOOL:
			return "true" if value else "false"
		TYPE_NIL:
			return "null"
		TYPE_STRING:
			return to_json(value)
		TYPE_ARRAY:
			var parts = []
			for v in value:
				parts.append(json(v))
			return "[" + PoolStringArray(parts).join(",") + "]"
		TYPE_DICTIONARY:
			var parts = []
			for k in value:
				parts.append(to_json(str(k)) + ":" + json(value[k]))
			return "{" + PoolStringArray(parts).join(",") + "}"
	return to_json(value)


# Level point (tiles, y up, from the level's corner) to Godot (pixels, y down, from the world's
# origin: the level sits at its `origin`, so a level far from the origin is far in Godot too).
# (GDScript's scalars are 64-bit; a Vector2 holds 32-bit floats, as Godot's positions do.)
func px(x, y):
	return Vector2((origin_x + x) * PIXELS_PER_TILE, -(origin_y + y) * PIXELS_PER_TILE)


# A point relative to a body (tiles, y up) to pixels, y down.
func local_px(x, y):
	return Vector2(x * PIXELS_PER_TILE, -y * PIXELS_PER_TILE)


# Godot position (pixels) back to a level point (tiles).
func level_point(p):
	return [p.x / PIXELS_PER_TILE - origin_x, -p.y / PIXELS_PER_TILE - origin_y]


# A rectangle [x0, y0, x1, y1] (tiles) as a shape of `owner`: in level coordinates for a body at
# the world's origin, or relative to `owner` when `local`.
func box_shape(owner, x0, y0, x1, y1, one_way, local = false):
	var shape = RectangleShape2D.new()
	shape.extents = Vector2((x1 - x0), (y1 - y0)) * PIXELS_PER_TILE / 2.0
	var node = CollisionShape2D.new()
	node.shape = shape
	var centre = [(x0 + x1) / 2.0, (y0 + y1) / 2.0]
	node.position = local_px(centre[0], centre[1]) if local else px(centre[0], centre[1])
	node.one_way_collision = one_way
	owner.add_child(node)


func static_body(layer, one_way):
	var body = StaticBody2D.new()
	body.collision_layer = layer
	body.collision_mask = 0
	body.set_meta("one_way", one_way)
	level_root.add_child(body)
	return body


func build(message):
	var level = message["level"]
	origin_x = float(level["origin"][0])
	origin_y = float(level["origin"][1])
	config = {}
	for c in configs():
		if c["label"] == message["config"]:
			config = c
	var label = config.get("label", "slide")
	level_root = Node2D.new()
	root.add_child(level_root)
	var solid = static_body(SOLID_LAYER, false)
	if label == "snap-merged":
		for b in level["solid_boxes"]:
			box_shape(solid, b[0], b[1], b[2], b[3], false)
	else:
		for t in level["solid_tiles"]:
			box_shape(solid, t[0], t[1], t[0] + 1, t[1] + 1, false)
	# A sloped tile's solid part, as a CollisionPolygon2D (build mode solids), which splits a
	# concave outline (a height-array tile's staircase) into convex parts as the editor's node
	# does.
	for s in level["slopes"]:
		var points = PoolVector2Array()
		for p in s["polygon"]:
			points.append(px(p[0], p[1]))
		var node = CollisionPolygon2D.new()
		node.build_mode = CollisionPolygon2D.BUILD_SOLIDS
		node.polygon = points
		solid.add_child(node)
	var one_way = static_body(ONE_WAY_LAYER, true)
	one_way_boxes = []
	for b in level["one_way"]:
		box_shape(one_way, b[0], b[1], b[2], b[3], true)
		one_way_boxes.append(b)
	platforms = []
	for p in level["platforms"]:
		var body = KinematicBody2D.new()
		body.collision_layer = ONE_WAY_LAYER if p["one_way"] else SOLID_LAYER
		body.collision_mask = 0
		body.set_meta("one_way", p["one_way"])
		body.set_meta("platform", platforms.size())
		body.set_meta("size", p["size"])
		body.set_sync_to_physics(true)
		box_shape(body, 0.0, 0.0, p["size"][0], p["size"][1], p["one_way"], true)
		body.position = px(p["start"][0], p["start"][1])
		level_root.add_child(body)
		platforms.append(body)
	characters = []
	dropping = []
	for c in message["characters"]:
		var body = KinematicBody2D.new()
		body.collision_layer = 0
		body.collision_mask = SOLID_LAYER | ONE_WAY_LAYER
		body.set_safe_margin(SAFE_MARGIN)
		var w = c["size"][0]
		var h = c["size"][1]
		box_shape(body, -w / 2.0, 0.0, w / 2.0, h, false, true)
		body.position = px(c["spawn"][0], c["spawn"][1])
		body.set_meta("size", c["size"])
		body.set_meta("on_platform", false)
		level_root.add_child(body)
		characters.append(body)
		dropping.append(false)


# Whether character `body`'s box overlaps a one-way tile or a one-way platform.
func in_one_way(body):
	var size = body.get_meta("size")
	var feet = level_point(body.position)
	var x0 = feet[0] - size[0] / 2.0
	var x1 = feet[0] + size[0] / 2.0
	var boxes = [] + one_way_boxes
	for p in platforms:
		if p.get_meta("one_way"):
			var at = level_point(p.position)
			var s = p.get_meta("size")
			boxes.append([at[0], at[1], at[0] + s[0], at[1] + s[1]])
	for b in boxes:
		if x0 < b[2] and x1 > b[0] and feet[1] < b[3] and feet[1] + size[1] > b[1]:
			return true
	return false


func step(message):
	var start = OS.get_ticks_usec()
	var label = config.get("label", "slide")
	var physics_dt = 1.0 / Engine.iterations_per_second
	var scale = message["dt"] / physics_dt
	for i in range(platforms.size()):
		var at = message["platforms"][i]
		platforms[i].position = px(at[0], at[1])
	var states = []
	for k in range(characters.size()):
		var body = characters[k]
		var request = message["characters"][k]
		# Down + jump on a one-way platform: a Godot game takes the one-way layer out of the
		# body's collision mask until the body is clear of one-way shapes (Godot 3 has no drop).
		if request.get("drop_through", false):
			dropping[k] = true
		elif dropping[k] and not in_one_way(body):
			dropping[k] = false
		body.collision_mask = SOLID_LAYER if dropping[k] else SOLID_LAYER | ONE_WAY_LAYER
		var desired = request["desired"]
		var v = Vector2(desired[0], -desired[1]) * PIXELS_PER_TILE * scale
		if label == "slide":
			v = body.move_and_slide(v, Vector2.UP)
		else:
			var snap = Vector2.ZERO if desired[1] > 0.0 else Vector2.DOWN * DEMO_SNAP
			var stop_on_slope = not body.get_meta("on_platform")
			v = body.move_and_slide_with_snap(v, snap, Vector2.UP, stop_on_slope, MAX_SLIDES, DEMO_FLOOR_MAX_ANGLE, false)
		states.append([body, v])
	var own = OS.get_ticks_usec() - start
	var out = []
	for pair in states:
		out.append(state_of(pair[0], pair[1] / scale))
	return {"type": "state", "step": int(message["step"]), "characters": out, "ns": int(own + engine_usec) * 1000}


# What Godot says about character `body` after its move.
func state_of(body, v):
	var grounded = body.is_on_floor()
	var floor_body = null
	if grounded:
		for i in range(body.get_slide_count()):
			var c = body.get_slide_collision(i)
			if c.normal.dot(Vector2.UP) > 0.5:
				floor_body = c.collider
		if floor_body == null:
			# Snapped to the floor: Godot 3 keeps the floor body private, so a short probe asks
			# what is underneath (test only: the body does not move), as the demo's
			# PlatformDetector ray does.
			var probe = body.move_and_collide(Vector2.DOWN * (2.0 * SAFE_MARGIN + 1.0), false, true, true)
			if probe != null:
				floor_body = probe.collider
	var platform = null
	var on_one_way = false
	if floor_body != null:
		on_one_way = floor_body.get_meta("one_way")
		if floor_body.has_meta("platform"):
			platform = floor_body.get_meta("platform")
	body.set_meta("on_platform", platform != null)
	var normal = body.get_floor_normal() if grounded else Vector2.ZERO
	var feet = level_point(body.position)
	return {
		"position": feet,
		"velocity": [v.x / PIXELS_PER_TILE, -v.y / PIXELS_PER_TILE],
		"grounded": grounded,
		"ground_normal": [normal.x, -normal.y],
		"wall": body.is_on_wall(),
		"ceiling": body.is_on_ceiling(),
		"on_one_way": on_one_way,
		"platform": platform,
	}


# One physics frame: read platbench's messages until a step is answered (the hello and run
# messages take a frame of their own). The time Godot spent between the previous frame's reply
# and this frame (its physics step, which moves the platforms, and its idle frame) is charged to
# this step with the script's own.
func _iteration(_delta):
	# Godot 3.2's SceneTree ignores what _iteration returns: only quit() ends it.
	if peer == null:
		quit()
		return true
	if frame_end >= 0:
		engine_usec = OS.get_ticks_usec() - frame_end
	var line = read_line()
	if line == null:
		quit()
		return true
	var parsed = JSON.parse(line)
	if parsed.error != OK or typeof(parsed.result) != TYPE_DICTIONARY:
		printerr("client.gd: not a message: ", line)
		quit(1)
		return true
	var message = parsed.result
	match message.get("type"):
		"hello":
			send(json({"type": "hello", "protocol": PROTOCOL, "name": "godot3",
				"description": "Godot " + Engine.get_version_info()["string"] + " KinematicBody2D (controllers/godot3/client.gd)",
				"configs": configs()}))
		"run":
			var features = message["level"]["features"]
			if features.get("ladders", false):
				send(json({"type": "refuse", "reason": "ladders: Godot 3 has no ladder state (a game scripts its own)"}))
			else:
				build(message)
				send(json({"type": "ready"}))
		"step":
			send(json(step(message)))
		"end":
			quit()
			return true
	frame_end = OS.get_ticks_usec()
	return false
