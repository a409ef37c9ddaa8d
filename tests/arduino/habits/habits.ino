// A student's habits, as the Arduino IDE builds them: the core's types, constants and helpers,
// PROGMEM, EEPROM, random(), pins, String, Serial's printing, a tab (helpers.ino) and a .cpp beside the
// sketch, a delay() before the robot begins and a loop that waits on millis(). Each line it
// prints is the same on the PC and on the board (tests/app/firmware_build_test.cc).
#include <EEPROM.h>
#include <UnimouseSim.h>

#include "three.h"

SimulationRobot robot(Serial);
const byte table[] PROGMEM = {10, 20, 30};
unsigned long startMs;
boolean spun = false;

int twice(int x);  // in the helpers tab

void setup() {
  Serial.begin(UNIMOUSE_BAUD);
  while (!Serial) {
  }
  const unsigned long early = millis();
  delay(200);  // "give the serial monitor a moment", before the robot begins
  robot.begin();
  startMs = millis();
  Serial.print("habit start ");
  Serial.print(early);
  Serial.print(' ');
  Serial.println(startMs);
  Serial.print("habit map ");
  Serial.print(map(512, 0, 1023, 0, 255));
  Serial.print(' ');
  Serial.println(map(50000, 0, 100000, 0, 100000));  // past 32 bits on the way
  Serial.print("habit constrain ");
  Serial.println(constrain(500, 0, 300));
  Serial.print("habit min max ");
  Serial.print(min(-2, 3));
  Serial.print(' ');
  Serial.println(max(7L, 1L));
  unsigned int v = 8;
  bitSet(v, 0);
  Serial.print("habit bits ");
  Serial.print(bitRead(5, 2));
  Serial.print(' ');
  Serial.print(v);
  bitClear(v, 0);
  Serial.print(' ');
  Serial.println(v);
  word w = word(highByte(513), lowByte(513));
  Serial.print("habit word ");
  Serial.println(w);
  Serial.print("habit progmem ");
  Serial.println(pgm_read_byte(&table[1]));
  Serial.print("habit eeprom ");
  Serial.print(EEPROM.read(100));
  EEPROM.put(0, 1234L);
  long back = 0;
  EEPROM.get(0, back);
  Serial.print(' ');
  Serial.println(back);
  randomSeed(42);
  Serial.print("habit random ");
  for (int i = 0; i < 3; ++i) {
    Serial.print(random(100));
    Serial.print(' ');
  }
  Serial.println(random(10, 20));
  pinMode(LED_BUILTIN, OUTPUT);
  digitalWrite(LED_BUILTIN, HIGH);
  Serial.print("habit pin ");
  Serial.print(digitalRead(LED_BUILTIN));
  digitalWrite(7, HIGH);  // a chip select high before it becomes an output
  pinMode(7, OUTPUT);
  Serial.print(' ');
  Serial.println(digitalRead(7));
  Serial.print("habit hex ");
  Serial.println(-1L, HEX);
  Serial.print("habit numbers ");
  Serial.print(2.5, 0);
  Serial.print(' ');
  Serial.print(1e12);
  Serial.print(' ');
  Serial.print(-INFINITY);
  Serial.print(' ');
  Serial.print(PI, 4);
  Serial.print(' ');
  Serial.print(-123456L);
  Serial.print(' ');
  Serial.print(sq(3) + abs(-4));
  Serial.print(' ');
  Serial.println(sq(byte(20)));
  String text = "v" + String(42) + String(' ') + String(255, HEX) + " " + String(3.14159, 3);
  text += 7;
  text.toUpperCase();
  Serial.print("habit string ");
  Serial.print(text);
  Serial.print(' ');
  Serial.print(text.length());
  Serial.print(' ');
  Serial.print(text.indexOf('F'));
  Serial.print(' ');
  Serial.println(String("  12ab ").toInt() + 1);
  Serial.print("habit parts ");
  Serial.print(twice(21));
  Serial.print(' ');
  Serial.println(addThree(4));
}

void loop() {
  robot.update();
  if (spun) return;
  spun = true;
  Serial.print("habit clock on ");
  Serial.println(millis() >= startMs ? "yes" : "no");
  // waiting as students do, on the clock alone
  const unsigned long t = millis();
  while (millis() - t < 50) {
  }
  Serial.println("habit spun 50 ms");
}
