//! What a level contains beyond solid tiles ([`Features`]), and how that compares with what a
//! backend models.

/// What a level contains beyond solid tiles; backends build and run only what is set here.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Features {
    /// The level has sloped tiles.
    pub slopes: bool,
    /// The level has one-way platforms.
    pub one_way: bool,
    /// The level has ladders.
    pub ladders: bool,
    /// The level has moving platforms.
    pub moving_platforms: bool,
}

impl Features {
    /// A level of solid tiles only.
    pub const NONE: Features = Features {
        slopes: false,
        one_way: false,
        ladders: false,
        moving_platforms: false,
    };

    /// Every feature the level format has.
    pub const ALL: Features = Features {
        slopes: true,
        one_way: true,
        ladders: true,
        moving_platforms: true,
    };

    /// Whether every feature set here is also set in `modelled`.
    pub fn within(&self, modelled: Features) -> bool {
        self.missing_from(modelled) == Features::NONE
    }

    /// The features set here and not in `modelled`.
    pub fn missing_from(&self, modelled: Features) -> Features {
        Features {
            slopes: self.slopes && !modelled.slopes,
            one_way: self.one_way && !modelled.one_way,
            ladders: self.ladders && !modelled.ladders,
            moving_platforms: self.moving_platforms && !modelled.moving_platforms,
        }
    }

    /// Names of the features that are set, for messages.
    pub fn names(&self) -> Vec<&'static str> {
        let mut v = Vec::new();
        if self.slopes {
            v.push("slopes");
        }
        if self.one_way {
            v.push("one-way platforms");
        }
        if self.ladders {
            v.push("ladders");
        }
        if self.moving_platforms {
            v.push("moving platforms");
        }
        v
    }
}
