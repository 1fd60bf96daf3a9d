// The USB host's side of a CDC-ACM serial port, on rp2040js's device-mode USB controller.
//
// rp2040js ships a CDC host (USBCDC), but two things of it do not suit embassy-usb (found by reading
// rp2040js 1.4.1's usb/cdc.ts): it sends SET_CONTROL_LINE_STATE to the device rather than to the
// communication interface (USB CDC PSTN 1.2, 6.3.12: bmRequestType 0x21), which embassy-usb's CDC-ACM
// class rightly ignores, so DTR never rises and accelcal's firmware (which drops frames while DTR is
// low) never answers; and it answers every OUT buffer the device arms at once, with zero bytes when it
// has none, which keeps the emulated CPU busy with empty packets. This host enumerates the device
// (address, configuration descriptor, configuration, DTR and RTS on the CDC interface), hands the bulk
// IN endpoint's data to `onData` while the host's port is open, sets DTR and RTS as the host opens
// and closes the port, and fills an armed OUT buffer only when it has bytes to send.

const SETUP_IN = 0x80;
const CLASS_INTERFACE_OUT = 0x21;
const GET_DESCRIPTOR = 6;
const SET_ADDRESS = 5;
const SET_CONFIGURATION = 9;
const SET_CONTROL_LINE_STATE = 0x22;
const CONFIGURATION_DESCRIPTOR = 2;
const INTERFACE_DESCRIPTOR = 4;
const ENDPOINT_DESCRIPTOR = 5;
const CDC_COMMUNICATION_CLASS = 0x02;
const CDC_DATA_CLASS = 0x0a;
const BULK = 2;
const DTR_AND_RTS = 0b11;
const LINES_DOWN = 0;
const DEVICE_ADDRESS = 1;

/** Where an OUT endpoint's buffer control register sits in the USB DPRAM (datasheet 4.1.2.5.1). */
const outBufferControl = (endpoint) => 0x84 + 8 * endpoint;
const BUFFER_AVAILABLE = 1 << 10;

/**
 * The hardware keeps an OUT buffer's AVAILABLE bit set until a packet from the host fills it, and
 * embassy-rp reads a cleared bit as "a packet arrived" (its `EndpointOut::read`). rp2040js 1.4.1
 * clears the bit as soon as the firmware arms the buffer, so embassy-rp took 64 bytes of nothing in a
 * loop. Here the bit is set again when the buffer is armed and cleared only when a packet is delivered.
 */
function keepOutBuffersAvailable(usb) {
  const dpram = usb.rp2040.usbDPRAMView;
  const armed = usb.onEndpointRead;
  usb.onEndpointRead = (endpoint, size) => {
    const at = outBufferControl(endpoint);
    dpram.setUint32(at, dpram.getUint32(at, true) | BUFFER_AVAILABLE, true);
    armed(endpoint, size);
  };
  const finishRead = usb.finishRead.bind(usb);
  usb.finishRead = (endpoint, buffer) => {
    const at = outBufferControl(endpoint);
    dpram.setUint32(at, dpram.getUint32(at, true) & ~BUFFER_AVAILABLE, true);
    finishRead(endpoint, buffer);
  };
}

/** An 8-byte SETUP packet (USB 2.0, 9.3). */
function setup(requestType, request, value, index, length) {
  return new Uint8Array([requestType, request, value & 0xff, value >> 8, index & 0xff, index >> 8, length & 0xff, length >> 8]);
}

/** The CDC interface number and the data interface's bulk endpoints, from a configuration descriptor. */
export function cdcEndpoints(descriptor) {
  const found = { control: -1, in: -1, out: -1 };
  let dataInterface = false;
  for (let at = 0; at + 1 < descriptor.length && descriptor[at] >= 2; at += descriptor[at]) {
    const [length, type] = [descriptor[at], descriptor[at + 1]];
    if (type === INTERFACE_DESCRIPTOR && length >= 9) {
      const interfaceClass = descriptor[at + 5];
      dataInterface = interfaceClass === CDC_DATA_CLASS;
      if (interfaceClass === CDC_COMMUNICATION_CLASS && found.control < 0) found.control = descriptor[at + 2];
    } else if (type === ENDPOINT_DESCRIPTOR && dataInterface && (descriptor[at + 3] & 0x3) === BULK) {
      const address = descriptor[at + 2];
      if (address & 0x80) found.in = address & 0xf;
      else found.out = address & 0xf;
    }
  }
  return found;
}

export class CdcHost {
  /** `onData(bytes)`: the device sent bytes; `onReady()`: the device is enumerated and configured. */
  constructor(usb, { onData, onReady }) {
    this.usb = usb;
    this.onData = onData;
    this.onReady = onReady;
    this.pending = [];
    this.portOpen = false;
    this.restart();
    usb.onUSBEnabled = () => usb.resetDevice();
    usb.onResetReceived = () => {
      this.restart();
      this.request(setup(0, SET_ADDRESS, DEVICE_ADDRESS, 0, 0), 'address');
    };
    usb.onEndpointWrite = (endpoint, bytes) => this.written(endpoint, bytes);
    usb.onEndpointRead = (endpoint, size) => this.armed(endpoint, size);
    keepOutBuffersAvailable(usb);
  }

  /** Forgets the enumeration (a bus reset). */
  restart() {
    this.stage = null;
    this.descriptor = [];
    this.descriptorLength = 0;
    this.endpoints = { control: -1, in: -1, out: -1 };
    this.outArmed = 0;
    this.ready = false;
  }

  /** Queues bytes for the device's bulk OUT endpoint. */
  send(bytes) {
    this.pending.push(...bytes);
    this.deliver();
  }

  /**
   * The host's program opened (true) or closed the port: as a host's CDC-ACM driver does, DTR and
   * RTS rise on open and fall on close (Linux's cdc-acm on the last close, with HUPCL).
   */
  setPortOpen(open) {
    this.portOpen = open;
    if (!open) this.pending = [];
    if (this.ready) this.sendLineState();
  }

  sendLineState() {
    const lines = this.portOpen ? DTR_AND_RTS : LINES_DOWN;
    this.request(setup(CLASS_INTERFACE_OUT, SET_CONTROL_LINE_STATE, lines, this.endpoints.control, 0), 'lines');
  }

  request(packet, stage) {
    this.stage = stage;
    this.usb.sendSetupPacket(packet);
  }

  /** The device wrote to an IN endpoint: a control stage, or serial data. */
  written(endpoint, bytes) {
    if (endpoint !== 0) {
      if (endpoint === this.endpoints.in && bytes.length > 0 && this.portOpen) this.onData(bytes);
      return;
    }
    if (this.stage === 'address') {
      this.request(setup(SETUP_IN, GET_DESCRIPTOR, CONFIGURATION_DESCRIPTOR << 8, 0, 9), 'header');
    } else if (this.stage === 'header' && bytes.length >= 4) {
      this.descriptorLength = bytes[2] | (bytes[3] << 8);
      this.request(setup(SETUP_IN, GET_DESCRIPTOR, CONFIGURATION_DESCRIPTOR << 8, 0, this.descriptorLength), 'descriptor');
    } else if (this.stage === 'descriptor') {
      this.descriptor.push(...bytes);
      if (this.descriptor.length >= this.descriptorLength) {
        this.endpoints = cdcEndpoints(this.descriptor);
        this.request(setup(0, SET_CONFIGURATION, 1, 0, 0), 'configuration');
      }
    } else if (this.stage === 'configuration') {
      this.stage = null;
      this.ready = true;
      this.sendLineState();
      this.onReady();
    } else if (this.stage === 'lines') {
      this.stage = null;
      this.deliver();
    }
  }

  /** The device armed an OUT buffer of `size` bytes: a control status stage, or room for serial data. */
  armed(endpoint, size) {
    if (endpoint === 0) {
      this.usb.endpointReadDone(0, new Uint8Array(0)); // the status stage of a control read
    } else if (endpoint === this.endpoints.out) {
      this.outArmed = size;
      this.deliver();
    }
  }

  deliver() {
    if (!this.ready || this.stage || this.outArmed === 0 || this.pending.length === 0) return;
    const chunk = new Uint8Array(this.pending.splice(0, this.outArmed));
    this.outArmed = 0;
    this.usb.endpointReadDone(this.endpoints.out, chunk);
  }
}
