use super::Claim;
pub fn claims() -> Vec<Claim> {
    vec![]
}
