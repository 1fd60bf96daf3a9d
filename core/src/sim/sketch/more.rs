//! The lines of the sketches issue 39 found refused (each as its source prints it; the print
//! statements are cited at each function): values among words, JSON and Python dictionaries, log
//! lines with colours and prefixes, a sample over several lines, CR alone, decimal commas.

use std::f64::consts::PI;

use super::super::person::ChipSample;

/// The chip's temperature counts as the sketches read them (about 26.5 degC: counts / 340 + 36.53,
/// register map 4.18).
const TEMP_COUNTS: f64 = -3400.0;

/// Degrees Celsius from the temperature counts (register map 4.18).
fn temp_c() -> f64 {
    TEMP_COUNTS / 340.0 + 36.53
}

/// Adafruit_MPU6050 at +-8 g and +-500 deg/s (as `basic_readings` sets it): m/s^2 and rad/s.
pub(super) fn adafruit_si(s: &ChipSample) -> ([f64; 3], [f64; 3]) {
    let ms2 = s.accel.map(|c| (f64::from(c) / 4.0).round() / 4096.0 * 9.80665);
    let rads = s.gyro.map(|c| (f64::from(c) / 2.0).round() / 65.5 * PI / 180.0);
    (ms2, rads)
}

/// The chip's counts as g and deg/s (+-2 g, +-250 deg/s).
fn g_dps(s: &ChipSample) -> ([f64; 3], [f64; 3]) {
    (s.accel.map(|c| f64::from(c) / 16384.0), s.gyro.map(|c| f64::from(c) / 131.0))
}

/// The Arduino Playground's "MPU-6050 Accelerometer + Gyro" short example (JohnChi, 2014):
/// `Serial.print("AcX = "); Serial.print(AcX); Serial.print(" | AcY = "); ... Serial.print(" | Tmp = ");
/// Serial.print(Tmp/340.00+36.53); ... Serial.print(" | GyZ = "); Serial.println(GyZ); delay(333);`
pub(super) fn playground(s: &ChipSample) -> String {
    let ([ax, ay, az], [gx, gy, gz]) = (s.accel, s.gyro);
    format!("AcX = {ax} | AcY = {ay} | AcZ = {az} | Tmp = {:.2} | GyX = {gx} | GyY = {gy} | GyZ = {gz}\r\n", temp_c())
}

/// Adafruit_MPU6050's `basic_readings` example: `Serial.print("Acceleration X: "); Serial.print(a.acceleration.x);
/// Serial.print(", Y: "); ... Serial.println(" m/s^2");`, the same for `Rotation` in `rad/s`,
/// `Serial.print("Temperature: "); Serial.print(temp.temperature); Serial.println(" degC");`, an empty
/// line, `delay(500)`.
pub(super) fn basic_readings(s: &ChipSample) -> String {
    let ([ax, ay, az], [gx, gy, gz]) = adafruit_si(s);
    format!(
        "Acceleration X: {ax:.2}, Y: {ay:.2}, Z: {az:.2} m/s^2\r\nRotation X: {gx:.2}, Y: {gy:.2}, Z: {gz:.2} rad/s\r\n\
         Temperature: {:.2} degC\r\n\r\n",
        temp_c()
    )
}

/// An ESP32 logger writing one ArduinoJson document a sample (`doc["t"] = millis(); doc["ax"] =
/// a.acceleration.x; ... serializeJson(doc, Serial); Serial.println();`): Adafruit_MPU6050's m/s^2
/// and rad/s, ArduinoJson's shortest round-trip decimals (here six significant digits).
pub(super) fn esp32_json(s: &ChipSample) -> String {
    let ([ax, ay, az], [gx, gy, gz]) = adafruit_si(s);
    let t = (s.at_s * 1000.0).round() as i64 + 1712;
    format!(
        "{{\"t\":{t},\"ax\":{ax:.5},\"ay\":{ay:.5},\"az\":{az:.5},\"gx\":{gx:.6},\"gy\":{gy:.6},\"gz\":{gz:.6},\"temp\":{:.2}}}\r\n",
        temp_c()
    )
}

/// MicroPython with adamjezek98's MPU6050-ESP8266-MicroPython `accel.get_values()` printed
/// (`print(accel.get_values())`): a dictionary of the raw counts, in the order MicroPython's dict
/// hashes its keys.
pub(super) fn micropython_dict(s: &ChipSample) -> String {
    let ([ax, ay, az], [gx, gy, gz]) = (s.accel, s.gyro);
    format!(
        "{{'GyZ': {gz}, 'GyY': {gy}, 'GyX': {gx}, 'Tmp': {:.4}, 'AcZ': {az}, 'AcY': {ay}, 'AcX': {ax}}}\r\n",
        temp_c()
    )
}

/// ESPHome's `mpu6050` sensor at its default DEBUG log level over USB serial: the component's
/// `ESP_LOGD(TAG, "Got accel={x=%.3f m/s², y=%.3f m/s², z=%.3f m/s²}, gyro={x=%.3f °/s, ...}, temp=%.3f°C")`
/// (esphome/components/mpu6050/mpu6050.cpp), then each sensor's `"'%s': Sending state %.5f %s with %d
/// decimals of accuracy"` (esphome/components/sensor/sensor.cpp), each line coloured by its level
/// (cyan `ESC[0;36m` for D, reset `ESC[0m`; esphome/core/log.h).
pub(super) fn esphome(s: &ChipSample) -> String {
    let (a, w) = g_dps(s);
    let ms2 = a.map(|v| v * 9.80665);
    let line = |text: String| format!("\u{1b}[0;36m[D][{text}\u{1b}[0m\r\n");
    let mut out = line(format!(
        "mpu6050:073]: Got accel={{x={:.3} m/s², y={:.3} m/s², z={:.3} m/s²}}, gyro={{x={:.3} °/s, y={:.3} °/s, z={:.3} °/s}}, temp={:.3}°C",
        ms2[0], ms2[1], ms2[2], w[0], w[1], w[2], temp_c()
    ));
    let sensors = [("Accel X", ms2[0], "m/s²"), ("Accel Y", ms2[1], "m/s²"), ("Accel Z", ms2[2], "m/s²")];
    let gyros = [("Gyro X", w[0], "°/s"), ("Gyro Y", w[1], "°/s"), ("Gyro Z", w[2], "°/s")];
    for (name, value, unit) in sensors.into_iter().chain(gyros).chain([("Temperature", temp_c(), "°C")]) {
        let decimals = if unit == "°C" { 1 } else { 2 };
        out += &line(format!(
            "sensor:093]: 'MPU6050 {name}': Sending state {value:.5} {unit} with {decimals} decimals of accuracy"
        ));
    }
    out
}

/// A logger ending its lines with a carriage return alone (`Serial.print('\r')`, as serial
/// terminals on old Macs and some data loggers expect): six counts, comma-separated.
pub(super) fn cr_only(s: &ChipSample) -> String {
    let ([ax, ay, az], [gx, gy, gz]) = (s.accel, s.gyro);
    format!("{ax},{ay},{az},{gx},{gy},{gz}\r")
}

/// A CSV written in a European locale (a PC logger's `f"{value:n}"` under de_DE, or a spreadsheet's
/// export): seconds, g and deg/s with decimal commas, separated by semicolons.
pub(super) fn semicolon_csv(s: &ChipSample) -> String {
    let (a, w) = g_dps(s);
    let values = [s.at_s, a[0], a[1], a[2], w[0], w[1], w[2]];
    let text: Vec<String> = values.iter().map(|v| format!("{v:.4}").replace('.', ",")).collect();
    format!("{}\r\n", text.join(";"))
}

/// Espressif's esp-iot-solution `mpu6050` component test (`mpu6050_test.c`):
/// `ESP_LOGI(TAG, "acce_x:%.2f, acce_y:%.2f, acce_z:%.2f\n", ...)` and `ESP_LOGI(TAG, "gyro_x:%.2f,
/// gyro_y:%.2f, gyro_z:%.2f\n", ...)` in g and deg/s, each line with ESP-IDF's prefix and colour
/// (`ESC[0;32mI (ms) tag: ... ESC[0m\n`, esp_log.h's LOG_FORMAT), the format's own `\n` an empty line.
pub(super) fn esp_idf(s: &ChipSample) -> String {
    let (a, w) = g_dps(s);
    let ms = (s.at_s * 1000.0) as u64 + 327;
    let log = |text: String| format!("\u{1b}[0;32mI ({ms}) mpu6050 test: {text}\n\u{1b}[0m\n");
    log(format!("acce_x:{:.2}, acce_y:{:.2}, acce_z:{:.2}", a[0], a[1], a[2]))
        + &log(format!("gyro_x:{:.2}, gyro_y:{:.2}, gyro_z:{:.2}", w[0], w[1], w[2]))
}

/// kriswiner's MPU6050IMU.ino: `Serial.print("X-acceleration: "); Serial.print(1000*ax);
/// Serial.print(" mg "); ...`, `Serial.print("X-gyro rate: "); Serial.print(gx, 1); Serial.print("
/// degrees/s "); ...`, `Serial.print("Temperature is "); Serial.print(temperature, 2);
/// Serial.println(" degrees C");`
pub(super) fn kriswiner(s: &ChipSample) -> String {
    let (a, w) = g_dps(s);
    let mg = a.map(|v| v * 1000.0);
    format!(
        "X-acceleration: {:.2} mg Y-acceleration: {:.2} mg Z-acceleration: {:.2} mg\r\n\
         X-gyro rate: {:.1} degrees/s Y-gyro rate: {:.1} degrees/s Z-gyro rate: {:.1} degrees/s\r\n\
         Temperature is {:.2} degrees C\r\n",
        mg[0],
        mg[1],
        mg[2],
        w[0],
        w[1],
        w[2],
        temp_c()
    )
}

/// A CircuitPython loop with adafruit_circuitpython_mpu6050 printing a list
/// (`print(list(mpu.acceleration) + list(mpu.gyro))`): m/s^2 and rad/s in Python's shortest repr.
pub(super) fn array(s: &ChipSample) -> String {
    let (ms2, rads) = adafruit_si(s);
    let text: Vec<String> = ms2.iter().chain(&rads).map(|v| format!("{v}")).collect();
    format!("[{}]\r\n", text.join(", "))
}

/// MicroPython printing several arguments (`print("Accel:", ax, ay, az, "Gyro:", gx, gy, gz)`), as
/// MicroPython MPU-6050 tutorials do: g and deg/s with print's float repr, space-separated.
pub(super) fn grouped(s: &ChipSample) -> String {
    let (a, w) = g_dps(s);
    let round = |v: f64| (v * 1e6).round() / 1e6;
    format!(
        "Accel: {} {} {} Gyro: {} {} {}\n",
        round(a[0]),
        round(a[1]),
        round(a[2]),
        round(w[0]),
        round(w[1]),
        round(w[2])
    )
}

/// The 14 bytes of the registers from ACCEL_XOUT_H on (register map 4.17-4.19), printed in their
/// order with no label (the Playground sketch's reads, `Serial.print(AcX); Serial.print("\t"); ...`):
/// accelerometer, temperature and gyro counts, tab-separated.
pub(super) fn registers(s: &ChipSample) -> String {
    let ([ax, ay, az], [gx, gy, gz]) = (s.accel, s.gyro);
    format!("{ax}\t{ay}\t{az}\t{}\t{gx}\t{gy}\t{gz}\r\n", TEMP_COUNTS as i64)
}
