pub mod corpus;
pub mod seeded;
