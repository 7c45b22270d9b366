//! The server's copy of a result element of CONTACT's library
//! (`ContactLibrary`): the library sends the calls made on its element and
//! asks for a calculation; this applies them to its copy with the same
//! code (`railcontact-cntc-core`) and calculates, so that the library gets
//! the numbers it would have computed in process. The stream plumbing
//! (order, idle timeout, session slots) is the handlers'.

use railcontact_cntc_core::element::Element;
use railcontact_cntc_core::error::CntcError;
use railcontact_cntc_core::remote::{self, Reply, Request, WireError, FORMAT_VERSION};
use railcontact_solver::core::cache::KernelCache;
use railcontact_solver::wheelrail::slices::SlicesLimits;

use crate::service::status::ServiceError;

/// A result element held by a `ContactLibrary` session.
pub struct LibraryElement {
    element: Element,
    /// The most grid elements the copy's patches may hold together.
    max_grid_elements: usize,
}

impl LibraryElement {
    /// The copy of an element of module `module` (1 or 3), its grids
    /// together at most `max_grid_elements` elements, the slices files it
    /// is sent (module 1) within `slices`.
    pub fn open(
        format_version: u32,
        module: i32,
        max_grid_elements: usize,
        slices: SlicesLimits,
    ) -> Result<Self, ServiceError> {
        if format_version != FORMAT_VERSION {
            return Err(ServiceError::precondition(
                "open.format_version",
                format!(
                    "open.format_version = {format_version}: this server reads payload version \
                     {FORMAT_VERSION}; use a library (contact_addon) of the server's release"
                ),
            ));
        }
        let mut element = Element::new(module).map_err(|e| {
            ServiceError::invalid("open.module", format!("{module}: {}", e.detail()))
        })?;
        if let Ok(w) = element.wheelrail_mut() {
            w.set_slices_limits(slices);
        }
        Ok(LibraryElement {
            element,
            max_grid_elements,
        })
    }

    /// The module of the element (1 or 3).
    pub fn module(&self) -> u8 {
        self.element.module()
    }

    /// Applies the calls of the encoded [`Request`] and calculates: the
    /// encoded [`Reply`]. A payload that does not decode is refused,
    /// naming `calculate.request`, before anything is applied.
    pub fn calculate(
        &mut self,
        request: &[u8],
        cache: &KernelCache,
    ) -> Result<Vec<u8>, ServiceError> {
        let req: Request = remote::decode(request, "request")
            .map_err(|e| ServiceError::invalid("calculate.request", e.detail()))?;
        let t0 = std::time::Instant::now();
        // The library applied each call already and told its caller what
        // failed; the copy applies the same calls to the same state, so it
        // fails the same ones, and keeps what they leave (a failed profile).
        for (icp, call) in &req.calls {
            let _ = call.apply(&mut self.element, *icp);
        }
        let code = self
            .check_grids()
            .and_then(|limit| self.element.calculate_within(req.icp, cache, limit));
        let result = self
            .element
            .calculation_result(req.icp)
            .map_err(|e| ServiceError::invalid("calculate.request.icp", e.detail()))?;
        let reply = Reply {
            code: code.map_err(|e| WireError::from(&e)),
            result,
            seconds: t0.elapsed().as_secs_f64(),
        };
        remote::encode(&reply).map_err(|e| ServiceError::Internal(e.to_string()))
    }

    /// The elements a patch's grid may have, once the patches configured
    /// (module 3) hold at most the limit together (module 1: one wheel's
    /// patches, solved one after the other, each within the limit).
    fn check_grids(&mut self) -> Result<usize, CntcError> {
        match &self.element {
            Element::WheelRail(_) => Ok(self.max_grid_elements),
            Element::Basic(patches) => {
                let total: usize = patches.values().filter_map(|p| p.grid_elements()).sum();
                if total > self.max_grid_elements {
                    return Err(CntcError::Discretisation(format!(
                        "the potential contact grids of this element's patches hold {total} \
                         elements together, more than the server's max_grid_elements = {}: use \
                         fewer elements or solve in process",
                        self.max_grid_elements
                    )));
                }
                Ok(self.max_grid_elements)
            }
        }
    }
}
