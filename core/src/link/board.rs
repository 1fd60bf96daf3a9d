//! One board's link: requests out under their ids over the host's [`Transport`], each answer taken
//! as its [`Call`] says, silence judged by frames at the host's times.

use shared::protocol::{Request, Response};

use super::{Call, Exchange, LinkError, Step, Transport};

/// A connection to one board over `T`.
pub struct Link<T: Transport> {
    transport: T,
    exchange: Exchange,
}

impl<T: Transport> Link<T> {
    /// A link over `transport`, opened now.
    pub fn new(transport: T) -> Self {
        let exchange = Exchange::new(transport.now());
        Link { transport, exchange }
    }

    /// The transport, for what the host adds to it (the Ctrl-C flag).
    pub fn transport_mut(&mut self) -> &mut T {
        &mut self.transport
    }

    /// The transport, given back (the host reads on from the port).
    pub fn into_transport(self) -> T {
        self.transport
    }

    /// The host's time, as the transport gives it.
    pub fn now(&self) -> std::time::Duration {
        self.transport.now()
    }

    /// Whether the person asked to stop (Ctrl-C), as the transport says.
    pub fn interrupted(&self) -> bool {
        self.transport.interrupted()
    }

    /// The date now, as the transport gives it, in seconds since the Unix epoch.
    pub fn unix_time_s(&self) -> f64 {
        self.transport.unix_time_s()
    }

    /// A request that completes at once: its final response; a device error becomes `Err`.
    pub async fn call(&mut self, request: Request) -> Result<Response, LinkError> {
        self.run(request, |_| {}).await
    }

    /// A request with progress (capture) or samples (stream): each goes to `on_update`; returns the
    /// final response. Fails when the device is silent for the silence limit.
    pub async fn run(&mut self, request: Request, mut on_update: impl FnMut(&Response)) -> Result<Response, LinkError> {
        self.run_while(request, |update| {
            on_update(update);
            true
        })
        .await
    }

    /// As [`Link::run`]; once `on_update` returns `false` the device is asked to stop, and its final
    /// response is still awaited (a cancelled stream ends with what it sent).
    pub async fn run_while(
        &mut self,
        request: Request,
        mut on_update: impl FnMut(&Response) -> bool,
    ) -> Result<Response, LinkError> {
        if self.transport.interrupted() {
            return Err(LinkError::Interrupted);
        }
        let id = self.send(&request).await?;
        self.exchange.listen(self.transport.now());
        let mut call = Call::new(id);
        loop {
            // NOTE: the device ends the cancelled operation with its final response, awaited below.
            if self.transport.interrupted() && call.interrupt() {
                self.cancel().await?;
            }
            let (answer_id, response) = self.receive().await.map_err(|error| call.failed(error))?;
            match call.answered(answer_id, response) {
                Step::Ignore => {}
                Step::Update(update) => {
                    if !on_update(&update) && call.decline() {
                        self.cancel().await?;
                    }
                }
                Step::Done(result) => return result,
            }
        }
    }

    /// Asks the device to stop its capture or stream (the running request then ends).
    pub async fn cancel(&mut self) -> Result<(), LinkError> {
        self.send(&Request::Cancel).await.map(|_| ())
    }

    /// Writes a leading frame delimiter, which ends any half frame an earlier session left in the
    /// board's buffer.
    pub async fn delimit(&mut self) -> Result<(), LinkError> {
        self.transport.write(&[0]).await
    }

    async fn send(&mut self, request: &Request) -> Result<u16, LinkError> {
        let (id, frame) = self.exchange.send(request)?;
        self.transport.write(&frame).await?;
        Ok(id)
    }

    /// The next answer (with the id it answers), reading until one comes or the silence limit passes.
    async fn receive(&mut self) -> Result<(u16, Response), LinkError> {
        let mut buffer = [0u8; 256];
        loop {
            if let Some(answer) = self.exchange.answer(self.transport.now())? {
                return Ok(answer);
            }
            let n = self.transport.read(&mut buffer).await?;
            self.exchange.received(&buffer[..n]);
        }
    }
}
