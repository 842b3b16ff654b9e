-- Wireshark / tshark dissector for the rcsim UDP stream, format rcsim-udp version 1
-- (schemas/udp-stream.md), with the target lists' elevation flag. Every datagram: a 32-byte little-endian header, then a payload by
-- message type. Found by its magic "RCSM" on any UDP port (heuristic), and on the UDP port set
-- in the preferences (Protocols > RCSIM > UDP port, default 0 = none).
--
--   tshark -r capture.pcap -X lua_script:tools/wireshark/rcsim.lua -Y rcsim
--   wireshark -X lua_script:tools/wireshark/rcsim.lua   (or copy into the personal plugins folder)

local rcsim = Proto("rcsim", "rcsim radar target list stream")

local message_types = {
  [0x01] = "simulated target list", [0x02] = "recorded target list", [0x03] = "ground truth",
  [0x04] = "end of stream", [0x05] = "control reply",
  [0x10] = "subscribe", [0x11] = "unsubscribe", [0x12] = "pause", [0x13] = "resume",
  [0x14] = "step", [0x15] = "seek", [0x16] = "keepalive",
}
local levels = { [0] = "ideal", [1] = "detections", [2] = "tracks", [3] = "recorded" }
local results = { [0] = "ok", [1] = "refused: clients full", [2] = "not subscribed", [3] = "out of range",
                  [4] = "not allowed: a watcher" }
local states = { [0] = "running", [1] = "paused", [2] = "finished" }

local f = rcsim.fields
f.magic = ProtoField.string("rcsim.magic", "Magic")
f.version = ProtoField.uint8("rcsim.version", "Version")
f.type = ProtoField.uint8("rcsim.type", "Message type", base.HEX, message_types)
f.flags = ProtoField.uint16("rcsim.flags", "Flags", base.HEX)
f.flag_late = ProtoField.bool("rcsim.flags.late", "Late", 16, nil, 0x0001)
f.sequence = ProtoField.uint64("rcsim.sequence", "Sequence number")
f.timestamp_ns = ProtoField.int64("rcsim.timestamp_ns", "Source timestamp (ns)")
f.message_number = ProtoField.uint32("rcsim.message_number", "Message number")
f.fragment_index = ProtoField.uint16("rcsim.fragment_index", "Fragment index")
f.fragment_count = ProtoField.uint16("rcsim.fragment_count", "Fragment count")

f.cycle = ProtoField.uint32("rcsim.cycle", "Cycle")
f.sensor_index = ProtoField.uint16("rcsim.sensor_index", "Sensor index")
f.level = ProtoField.uint8("rcsim.level", "Level", base.DEC, levels)
f.sensor_id_length = ProtoField.uint8("rcsim.sensor_id_length", "Sensor id length")
f.total_count = ProtoField.uint32("rcsim.total_count", "Items in the message")
f.first_index = ProtoField.uint32("rcsim.first_index", "First item in this fragment")
f.count = ProtoField.uint16("rcsim.count", "Items in this fragment")
f.sensor_id = ProtoField.string("rcsim.sensor_id", "Sensor id")
f.target = ProtoField.none("rcsim.target", "Target")
f.target_id = ProtoField.int32("rcsim.target.id", "Id")
f.range_m = ProtoField.double("rcsim.target.range_m", "Range (m)")
f.azimuth_rad = ProtoField.double("rcsim.target.azimuth_rad", "Azimuth (rad)")
f.range_rate_mps = ProtoField.double("rcsim.target.range_rate_mps", "Range rate (m/s)")
f.amplitude_db = ProtoField.double("rcsim.target.amplitude_db", "Amplitude (dB)")
f.elevation_rad = ProtoField.double("rcsim.target.elevation_rad", "Elevation (rad)")
f.list_flags = ProtoField.uint16("rcsim.list_flags", "List flags", base.HEX)
f.list_flag_elevation = ProtoField.bool("rcsim.list_flags.elevation", "Targets carry elevation", 16, nil, 0x0001)

f.ego = ProtoField.none("rcsim.ego", "Ego")
f.object = ProtoField.none("rcsim.object", "Object")
f.object_index = ProtoField.uint32("rcsim.object.index", "Object index")
f.object_id = ProtoField.string("rcsim.object.id", "Object id")
f.x_m = ProtoField.double("rcsim.x_m", "x (m)")
f.y_m = ProtoField.double("rcsim.y_m", "y (m)")
f.yaw_rad = ProtoField.double("rcsim.yaw_rad", "Yaw (rad)")
f.speed_mps = ProtoField.double("rcsim.speed_mps", "Speed (m/s)")
f.length_m = ProtoField.double("rcsim.object.length_m", "Length (m)")
f.width_m = ProtoField.double("rcsim.object.width_m", "Width (m)")

f.end_datagrams = ProtoField.uint64("rcsim.end.datagrams_sent", "Datagrams sent before this one")
f.end_messages = ProtoField.uint32("rcsim.end.messages_sent", "Messages sent")
f.end_cycles = ProtoField.uint32("rcsim.end.cycles_sent", "Cycles sent")
f.end_late = ProtoField.uint32("rcsim.end.late_cycles", "Late cycles")

f.reply_sequence = ProtoField.uint64("rcsim.reply.request_sequence", "Request sequence number")
f.reply_type = ProtoField.uint8("rcsim.reply.request_type", "Request type", base.HEX, message_types)
f.reply_result = ProtoField.uint8("rcsim.reply.result", "Result", base.DEC, results)
f.reply_state = ProtoField.uint8("rcsim.reply.state", "State", base.DEC, states)
f.reply_next_cycle = ProtoField.uint32("rcsim.reply.next_cycle", "Next cycle")
f.reply_cycle_count = ProtoField.uint32("rcsim.reply.cycle_count", "Cycle count")
f.reply_subscribers = ProtoField.uint32("rcsim.reply.subscribers", "Subscribers")
f.reply_ignored = ProtoField.uint64("rcsim.reply.control_ignored", "Control datagrams ignored")

f.control_mask = ProtoField.uint32("rcsim.control.message_mask", "Message mask", base.HEX)
f.control_sensor_mask = ProtoField.uint32("rcsim.control.sensor_mask", "Sensor mask", base.HEX)
f.control_argument = ProtoField.uint32("rcsim.control.argument", "Argument")
f.control_token_length = ProtoField.uint8("rcsim.control.token_length", "Control token length")

local e_malformed = ProtoExpert.new("rcsim.malformed", "Malformed rcsim payload", expert.group.MALFORMED, expert.severity.ERROR)
rcsim.experts = { e_malformed }

local port_pref = 0
rcsim.prefs.port = Pref.uint("UDP port", 0, "Decode this UDP port as rcsim (0: magic-based detection only)")

local function pose(tree, buf, at)
  tree:add_le(f.x_m, buf(at, 8))
  tree:add_le(f.y_m, buf(at + 8, 8))
  tree:add_le(f.yaw_rad, buf(at + 16, 8))
  tree:add_le(f.speed_mps, buf(at + 24, 8))
end

local function target_list(buf, tree, pinfo)
  if buf:len() < 20 then return false end
  local id_length = buf(7, 1):uint()
  local n = buf(16, 2):le_uint()
  local list_flags = buf(18, 2):le_uint()
  if list_flags > 1 then return false end
  local elevation = list_flags == 1
  local size = elevation and 44 or 36  -- 44: elevation_rad as a fifth f64 (issue 49)
  if buf:len() ~= 20 + id_length + size * n then return false end
  tree:add_le(f.cycle, buf(0, 4))
  tree:add_le(f.sensor_index, buf(4, 2))
  tree:add_le(f.level, buf(6, 1))
  tree:add_le(f.sensor_id_length, buf(7, 1))
  tree:add_le(f.total_count, buf(8, 4))
  tree:add_le(f.first_index, buf(12, 4))
  tree:add_le(f.count, buf(16, 2))
  local flags = tree:add_le(f.list_flags, buf(18, 2))
  flags:add_le(f.list_flag_elevation, buf(18, 2))
  tree:add(f.sensor_id, buf(20, id_length))
  local at = 20 + id_length
  for i = 0, n - 1 do
    local t = tree:add(f.target, buf(at, size))
    local text = string.format("Target %d: id %d, %.3f m, %.4f rad, %.3f m/s, %.2f dB",
      buf(12, 4):le_uint() + i, buf(at, 4):le_int(), buf(at + 4, 8):le_float(), buf(at + 12, 8):le_float(),
      buf(at + 20, 8):le_float(), buf(at + 28, 8):le_float())
    if elevation then text = text .. string.format(", elevation %.4f rad", buf(at + 36, 8):le_float()) end
    t:set_text(text)
    t:add_le(f.target_id, buf(at, 4))
    t:add_le(f.range_m, buf(at + 4, 8))
    t:add_le(f.azimuth_rad, buf(at + 12, 8))
    t:add_le(f.range_rate_mps, buf(at + 20, 8))
    t:add_le(f.amplitude_db, buf(at + 28, 8))
    if elevation then t:add_le(f.elevation_rad, buf(at + 36, 8)) end
    at = at + size
  end
  pinfo.cols.info:append(string.format(" cycle %d, %s, %d targets", buf(0, 4):le_uint(), buf(20, id_length):string(), n))
  return true
end

local function ground_truth(buf, tree, pinfo)
  if buf:len() < 48 then return false end
  tree:add_le(f.cycle, buf(0, 4))
  tree:add_le(f.total_count, buf(4, 4))
  tree:add_le(f.first_index, buf(8, 4))
  tree:add_le(f.count, buf(12, 2))
  pose(tree:add(f.ego, buf(16, 32)), buf, 16)
  local n = buf(12, 2):le_uint()
  local at = 48
  for _ = 1, n do
    if buf:len() < at + 53 then return false end
    local id_length = buf(at + 52, 1):uint()
    if buf:len() < at + 53 + id_length then return false end
    local o = tree:add(f.object, buf(at, 53 + id_length))
    o:add_le(f.object_index, buf(at, 4))
    pose(o, buf, at + 4)
    o:add_le(f.length_m, buf(at + 36, 8))
    o:add_le(f.width_m, buf(at + 44, 8))
    o:add(f.object_id, buf(at + 53, id_length))
    o:set_text("Object " .. buf(at + 53, id_length):string())
    at = at + 53 + id_length
  end
  pinfo.cols.info:append(string.format(" cycle %d, %d objects", buf(0, 4):le_uint(), n))
  return at == buf:len()
end

local function dissect(buf, pinfo, root)
  if buf:len() < 32 or buf(0, 4):string() ~= "RCSM" then return 0 end
  pinfo.cols.protocol = "RCSIM"
  local tree = root:add(rcsim, buf(), "rcsim stream")
  local header = tree:add(buf(0, 32), "Header")
  header:add(f.magic, buf(0, 4))
  header:add_le(f.version, buf(4, 1))
  local type = buf(5, 1):uint()
  header:add_le(f.type, buf(5, 1))
  local flags = header:add_le(f.flags, buf(6, 2))
  flags:add_le(f.flag_late, buf(6, 2))
  header:add_le(f.sequence, buf(8, 8))
  header:add_le(f.timestamp_ns, buf(16, 8))
  header:add_le(f.message_number, buf(24, 4))
  header:add_le(f.fragment_index, buf(28, 2))
  header:add_le(f.fragment_count, buf(30, 2))
  pinfo.cols.info = string.format("%s seq %s frag %d/%d", message_types[type] or string.format("type 0x%02x", type),
    tostring(buf(8, 8):le_uint64()), buf(28, 2):le_uint() + 1, buf(30, 2):le_uint())
  if buf(4, 1):uint() ~= 1 then
    tree:add_proto_expert_info(e_malformed, "unknown version")
    return buf:len()
  end
  local payload = buf:len() > 32 and buf(32) or nil
  local ok = true
  if type == 0x01 or type == 0x02 then
    ok = payload ~= nil and target_list(payload, tree, pinfo)
  elseif type == 0x03 then
    ok = payload ~= nil and ground_truth(payload, tree, pinfo)
  elseif type == 0x04 then
    ok = payload ~= nil and payload:len() == 24
    if ok then
      tree:add_le(f.end_datagrams, payload(0, 8))
      tree:add_le(f.end_messages, payload(8, 4))
      tree:add_le(f.end_cycles, payload(12, 4))
      tree:add_le(f.end_late, payload(16, 4))
    end
  elseif type == 0x05 then
    ok = payload ~= nil and payload:len() == 32
    if ok then
      tree:add_le(f.reply_sequence, payload(0, 8))
      tree:add_le(f.reply_type, payload(8, 1))
      tree:add_le(f.reply_result, payload(9, 1))
      tree:add_le(f.reply_state, payload(10, 1))
      tree:add_le(f.reply_next_cycle, payload(12, 4))
      tree:add_le(f.reply_cycle_count, payload(16, 4))
      tree:add_le(f.reply_subscribers, payload(20, 4))
      tree:add_le(f.reply_ignored, payload(24, 8))
    end
  elseif type == 0x10 then
    -- 8 bytes, or 8 + 1 + a 16..64-byte control token (shown by its length only)
    local n = payload ~= nil and payload:len() or 0
    ok = n == 8 or (n >= 9 + 16 and n <= 9 + 64 and payload(8, 1):uint() == n - 9)
    if ok then
      tree:add_le(f.control_mask, payload(0, 4))
      tree:add_le(f.control_sensor_mask, payload(4, 4))
      if n > 8 then tree:add(f.control_token_length, payload(8, 1)) end
    end
  elseif type == 0x14 or type == 0x15 then
    ok = payload ~= nil and payload:len() == 4
    if ok then tree:add_le(f.control_argument, payload(0, 4)) end
  elseif type >= 0x11 and type <= 0x16 then
    ok = payload == nil
  else
    ok = false
  end
  if not ok then tree:add_proto_expert_info(e_malformed) end
  return buf:len()
end

function rcsim.dissector(buf, pinfo, root) return dissect(buf, pinfo, root) end

local function heuristic(buf, pinfo, root)
  if buf:len() < 32 or buf(0, 4):string() ~= "RCSM" then return false end
  dissect(buf, pinfo, root)
  return true
end
rcsim:register_heuristic("udp", heuristic)

function rcsim.prefs_changed()
  local udp_table = DissectorTable.get("udp.port")
  if port_pref ~= 0 then udp_table:remove(port_pref, rcsim) end
  port_pref = rcsim.prefs.port
  if port_pref ~= 0 then udp_table:add(port_pref, rcsim) end
end
